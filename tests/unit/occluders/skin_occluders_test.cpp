// SPDX-License-Identifier: MIT
// Skins in the frame: drawing them nearest first and skipping those already
// hidden leaves the depth buffer exactly as drawing every usable skin in
// the frustum would (a hidden skin has no pixel nearer than what is there);
// a skin whose mesh the near plane cuts, or whose mesh holds the eye, is
// not usable.
#include "occluders/skin_occluders.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "camera/route.h"
#include "occluders/occluder_skins.h"
#include "scene/city.h"

using namespace occu;

TEST(SkinOccluders, SkippingHiddenSkinsChangesNoDepthPixel)
{
    CityOptions city;
    city.blocks_x = city.blocks_z = 3;
    const Scene scene = generate_city(city);
    SkinOccluders skins(scene, "", 8);
    ASSERT_GT(skins.size(), 50u);
    DepthRasterizer skipping, every;
    std::vector<float> a, b;
    std::size_t drawn = 0, in_frustum = 0;
    for (const char *route : {"dense", "street", "random:8:7"}) {
        for (const Camera &camera : make_route(route, scene.bounds, city, 8, 1.0f)) {
            const Frame frame(camera, 128, 128);
            for (int divisor : {1, 2}) {
                skipping.begin(frame.view_projection, 128, 128, {divisor, true});
                drawn += skins.render(frame, skipping, 0);
                every.begin(frame.view_projection, 128, 128, {divisor, true});
                for (std::size_t i = 0; i < skins.size(); ++i)
                    if (frame.frustum.classify(skins.boxes()[i]) != Frustum::Side::outside && skins.usable(i, frame)) {
                        every.render_box(skins.boxes()[i]);
                        ++in_frustum;
                    }
                skipping.read(a);
                every.read(b);
                ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << route;
            }
        }
    }
    EXPECT_LT(drawn * 2, in_frustum) << "at street level most skins stand behind others";
}

TEST(SkinOccluders, RefusesADatabaseMadeForAnotherScene)
{
    CityOptions small;
    small.blocks_x = small.blocks_z = 1;
    const Scene one = generate_city(small);
    small.seed = 7;
    const Scene other = generate_city(small);
    const std::string path = ::testing::TempDir() + "skins-of-one.txt";
    OccluderSkinDatabase::make(one, SkinOptions{}).save(path);
    EXPECT_NO_THROW(SkinOccluders(one, path, 8));
    try {
        SkinOccluders(other, path, 8);
        FAIL() << "a database of another scene was taken";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    std::remove(path.c_str());
}

TEST(SkinOccluders, ASkinIsUnusableWhereTheNearPlaneCutsItsMeshOrTheEyeIsInside)
{
    Scene scene;
    scene.meshes.emplace_back();
    append_box(scene.meshes[0], Aabb::of({-5, 0, -30}, {5, 10, -20}));
    scene.update_bounds();
    SkinOccluders skins(scene, "", 8);
    ASSERT_EQ(skins.size(), 1u);
    Camera c;
    c.position = {0, 5, 0};
    c.target = {0, 5, -1};
    c.near_plane = 0.5f;
    EXPECT_TRUE(skins.usable(0, Frame(c, 64, 64))) << "the mesh lies 20 m beyond the near plane";
    c.near_plane = 20.5f;
    EXPECT_FALSE(skins.usable(0, Frame(c, 64, 64))) << "the near plane cuts the mesh's front wall away";
    c.near_plane = 0.5f;
    c.position = {0, 5, -25};
    c.target = {0, 5, -26};
    EXPECT_FALSE(skins.usable(0, Frame(c, 64, 64))) << "the eye is inside the mesh";
}
