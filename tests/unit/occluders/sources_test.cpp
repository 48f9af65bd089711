// SPDX-License-Identifier: MIT
// The shared occluder sources (occluders/sources.h) reach the families
// through what a family declares: every family that names a source has
// each of its settings once, the source's database is read only where the
// family's settings take occluders from it, and a setting the family
// declares itself is not added twice; and scene-triangles, the scene's own
// triangles at the defaults, joins the skins where they leave most of it out.
#include "occluders/sources.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "culling/databases.h"
#include "occluders/depth_occluders.h"

using namespace occu;

namespace {

long count_of(const std::vector<SettingSpec> &specs, const std::string &name)
{
    return std::count_if(specs.begin(), specs.end(), [&](const SettingSpec &s) { return s.name == name; });
}

// A quad a, b, c, d, counter-clockwise seen from its front.
void add_quad(Mesh &m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d)
{
    const auto first = std::uint32_t(m.positions.size());
    for (const glm::vec3 &p : {a, b, c, d}) {
        m.positions.push_back(p);
        m.normals.push_back(glm::vec3(0, 0, 1));
    }
    m.indices.insert(m.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
}

Mesh closed_box(const Aabb &box)
{
    Mesh m;
    for (const auto &face : aabb_faces)
        add_quad(m, box.corner(face[0]), box.corner(face[1]), box.corner(face[2]), box.corner(face[3]));
    return m;
}

// How many occluders DepthOccluders draws at the defaults of the skin and
// triangle sources, with scene-triangles on or off, from (0, 2, 0) down -z.
std::size_t occluders_drawn(const Scene &scene, bool scene_triangles)
{
    std::vector<SettingSpec> specs = skin_settings();
    for (const SettingSpec &s : triangle_occluder_source().settings)
        specs.push_back(s);
    Settings settings("test", &specs);
    settings.set("scene-triangles", scene_triangles ? "on" : "off");
    DepthOccluders occluders(scene, settings);
    Camera camera;
    camera.position = {0, 2, 0};
    camera.target = {0, 2, -1};
    camera.near_plane = 0.5f;
    const Frame frame(camera, 96, 96);
    DepthRasterizer raster;
    raster.begin(frame.view_projection, 96, 96, {2, true, false});
    return occluders.render(frame, raster, 0);
}

Scene scene_of(std::vector<Mesh> meshes)
{
    Scene scene;
    for (Mesh &m : meshes) {
        m.update_bounds();
        scene.meshes.push_back(std::move(m));
    }
    scene.update_bounds();
    return scene;
}

}  // namespace

// scene-triangles at the defaults, mesh by mesh: where meshes without
// skins (open walls, as most of the IFC house's 294 meshes) hold most of
// the scene's occluder triangles, its own triangles join the skins of the
// closed meshes; where they hold few (the city's ground: 12 of 272,796),
// the skins stand alone.
TEST(OccluderSources, SceneTrianglesJoinTheSkinsWhereMeshesWithoutSkinsHoldMostTriangles)
{
    Mesh wall;   // open, 10 x 10 quads facing the eye, beside the box
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) {
            const float x = -8.0f + 0.5f * float(i), y = 0.5f * float(j);
            add_quad(wall, {x, y, -10}, {x + 0.5f, y, -10}, {x + 0.5f, y + 0.5f, -10}, {x, y + 0.5f, -10});
        }
    const Mesh box = closed_box(Aabb::of({-2, 0, -14}, {2, 4, -10}));
    const Scene walls = scene_of({box, wall});
    ASSERT_GT(SkinOccluders(walls, "", 8).size(), 0u) << "the box has a skin";
    EXPECT_GT(occluders_drawn(walls, true), occluders_drawn(walls, false))
        << "200 of the 212 triangles have no skin, and none of them joined the box's skin";

    Mesh ground;   // open, two triangles facing up
    add_quad(ground, {-5, 0, -5}, {5, 0, -5}, {5, 0, -20}, {-5, 0, -20});
    const Scene city_like = scene_of({box, ground});
    EXPECT_EQ(occluders_drawn(city_like, true), occluders_drawn(city_like, false))
        << "2 of the 14 triangles have no skin: the skins stand alone";
}

TEST(OccluderSources, EveryFamilyThatNamesASourceHasItsSettingsOnce)
{
    std::set<std::string> skin_users;
    for (const StrategyFamily &f : strategy_families())
        for (const OccluderSourceUse &use : f.occluder_sources) {
            ASSERT_NE(use.source, nullptr) << f.name;
            if (use.source == &skin_occluder_source())
                skin_users.insert(f.name);
            for (const SettingSpec &s : use.source->settings)
                EXPECT_EQ(count_of(f.settings, s.name), 1) << f.name << " " << s.name;
            for (const DatabaseNeed &d : use.source->databases)
                EXPECT_EQ(std::count_if(f.databases.begin(), f.databases.end(),
                                        [&](const DatabaseNeed &e) { return e.setting == d.setting; }),
                          1)
                    << f.name << " " << d.setting;
        }
    EXPECT_EQ(skin_users, (std::set<std::string>{"skins", "hzb", "hom", "shadow", "planes"}));
}

TEST(OccluderSources, ASourcesDatabaseIsReadOnlyWhereTheFamilyDrawsFromIt)
{
    auto reads_skins = [](const std::string &spec) {
        const StrategyChoice choice = choose_strategy(spec);
        const std::vector<const DatabaseNeed *> read = databases_read(choice);
        return std::any_of(read.begin(), read.end(), [](const DatabaseNeed *d) { return d->setting == "skin-database"; });
    };
    EXPECT_TRUE(reads_skins("skins"));
    EXPECT_TRUE(reads_skins("skins-both"));
    EXPECT_FALSE(reads_skins("skins-drawn"));
    EXPECT_TRUE(reads_skins("hzb"));
    EXPECT_FALSE(reads_skins("hzb-last-frame"));
    EXPECT_TRUE(reads_skins("hom"));
    EXPECT_TRUE(reads_skins("shadow"));
    EXPECT_TRUE(reads_skins("planes:skin-source=brushes"));
    EXPECT_FALSE(reads_skins("ou"));
}

TEST(OccluderSources, AFamilysOwnSettingIsNotAddedTwice)
{
    StrategyFamily f;
    f.name = "test";
    f.settings = {integer_setting("skin-boxes", 2, 1, 4, SettingSpec::Role::cost, "the family's own")};
    f.occluder_sources = {{&skin_occluder_source()}};
    const std::vector<StrategyFamily> done = with_occluder_sources({std::move(f)});
    ASSERT_EQ(done.size(), 1u);
    EXPECT_EQ(count_of(done[0].settings, "skin-boxes"), 1);
    EXPECT_EQ(done[0].settings[0].help, "the family's own");
    EXPECT_EQ(count_of(done[0].settings, "skin-voxel"), 1);
    EXPECT_EQ(done[0].databases.size(), 1u);
}
