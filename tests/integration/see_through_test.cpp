// SPDX-License-Identifier: MIT
// A see-through mesh (Mesh::occluder false: a Quake III level's glass,
// water or fog, scene/quake3_bsp.h) is drawn but hides nothing: what lies
// behind it shows through it in the frame, the oracle counts it visible, no
// strategy culls it, and no preprocessing step makes an occluder of the
// see-through mesh. The scene: a solid block of glass, thick enough for
// occluder skins and covering the whole view of an opaque box behind it,
// and nothing else. Every conservative strategy of the registry and test
// variant of its family (culling/registry.h), in batches of one and of its
// own, must draw the box and lose no pixel against the unculled frame (as
// the measurement session counts them); a strategy that
// cannot serve the scene must refuse it with a reason. Runs on the driver
// meson selects with GALLIUM_DRIVER.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "culling/registry.h"
#include "evaluation/lost_pixels.h"
#include "evaluation/measurement_session.h"
#include "evaluation/oracle.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "occluders/occluder_skins.h"
#include "occluders/skin_occluders.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"
#include "strategies/poon_wang_opacity_maps/occluder_database.h"
#include "strategies/poon_wang_opacity_maps/view_preprocessing.h"

#include "strategy_variants.h"

using namespace occu;

namespace {

constexpr int size = 64;
constexpr std::uint32_t glass_mesh = 0, box_mesh = 1;
const Aabb glass_bounds = Aabb::of({-3, -3, -6}, {3, 3, -4});   // 2 m thick: skins fill it when it counts
const Aabb box_bounds = Aabb::of({-1.5f, -1.5f, -13}, {1.5f, 1.5f, -10});

Camera eye()
{
    Camera c;
    c.position = {0, 0, 0};
    c.target = {0, 0, -1};
    c.near_plane = 0.5f;
    c.far_plane = 100.0f;
    return c;
}

Scene glass_before_box(bool with_box = true)
{
    Scene scene;
    Mesh glass;
    glass.name = "glass";
    glass.color = {0.3f, 0.6f, 0.9f};
    glass.occluder = false;
    append_box(glass, glass_bounds);
    scene.meshes.push_back(std::move(glass));
    if (with_box) {
        Mesh box;
        box.name = "box";
        box.color = {0.9f, 0.3f, 0.1f};
        append_box(box, box_bounds);
        scene.meshes.push_back(std::move(box));
    }
    for (Mesh &m : scene.meshes)
        m.update_bounds();
    scene.update_bounds();
    return scene;
}

// Leaves of 12 triangles at most: the glass and the box in leaves of their own.
HierarchyOptions leaves_of_12_triangles()
{
    HierarchyOptions options;
    options.max_leaf_triangles = 12;
    return options;
}

Hierarchy hierarchy_of(const Scene &scene)
{
    return Hierarchy::build(scene, leaves_of_12_triangles());
}

// The leaves holding triangles of mesh `mesh`.
std::vector<std::uint32_t> leaves_of(const Hierarchy &h, std::uint32_t mesh)
{
    std::vector<std::uint32_t> leaves;
    for (std::uint32_t n = 0; n < h.nodes().size(); ++n) {
        const HierarchyNode &node = h.nodes()[n];
        for (std::uint32_t t = 0; node.leaf() && t < node.triangle_count; ++t)
            if (h.triangles()[node.first_triangle + t].mesh == mesh) {
                leaves.push_back(n);
                break;
            }
    }
    return leaves;
}

bool holds_any(const std::vector<std::uint32_t> &set, const std::vector<std::uint32_t> &of)
{
    return std::any_of(of.begin(), of.end(), [&](std::uint32_t n) { return std::count(set.begin(), set.end(), n) > 0; });
}

std::string listed(const std::vector<std::uint32_t> &nodes)
{
    std::string s;
    for (std::uint32_t n : nodes)
        s += " " + std::to_string(n);
    return s.empty() ? " none" : s;
}

void frame_state()
{
    glViewport(0, 0, size, size);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glClearColor(0, 0, 0, 0);
}

// The pixel at the middle of a frame, RGBA8.
std::vector<std::uint8_t> middle(const std::uint8_t *pixels)
{
    const std::size_t i = 4 * (std::size_t(size / 2) * size + size / 2);
    return {pixels + i, pixels + i + 4};
}

}  // namespace

TEST(SeeThrough, SkinPreprocessingMakesNoOccluderOfASeeThroughMesh)
{
    const Scene scene = glass_before_box();
    const SceneSkins skins = scene_skins(scene, SkinOptions{});
    bool box_has_skins = false;
    for (const MeshSkins &m : skins.skins) {
        EXPECT_NE(m.mesh, glass_mesh) << "the glass got " << m.boxes.size() << " skin boxes";
        box_has_skins |= m.mesh == box_mesh && !m.boxes.empty();
    }
    EXPECT_TRUE(box_has_skins) << "the opaque box, a closed 3 m cube, got no skins: the test means nothing";
    // What the run time takes as occluders (shared by skins, hzb, hom, shadow, planes).
    const SkinOccluders occluders(scene, "", 8);
    ASSERT_FALSE(occluders.boxes().empty());
    for (const Aabb &b : occluders.boxes())
        EXPECT_TRUE(box_bounds.contains(b.min) && box_bounds.contains(b.max))
            << "an occluder box lies outside the opaque box";
}

TEST(SeeThrough, MinimumOccluderSetsTakeNoSeeThroughLeaf)
{
    gl::OffscreenContext ctx(size, size);
    const Scene scene = glass_before_box();
    const Hierarchy h = hierarchy_of(scene);
    const SceneRenderer renderer(scene, h);
    PreprocessOptions pre;
    pre.stacks.resolution = size / pre.stacks.map_divisor;
    pre.stacks.min_occludee_triangles = 4;   // the box is an occludee if anything hides it
    pre.stacks.min_occluder_pixels = 1;
    const std::vector<std::uint32_t> chosen = select_occluders_for_view(renderer, h, eye(), pre);
    EXPECT_FALSE(holds_any(chosen, leaves_of(h, glass_mesh)))
        << "occluders chosen:" << listed(chosen) << "; glass leaves:" << listed(leaves_of(h, glass_mesh));
}

TEST(SeeThrough, TheOracleSeesWhatLiesBehindASeeThroughMesh)
{
    gl::OffscreenContext ctx(size, size);
    frame_state();
    const Scene scene = glass_before_box();
    const Hierarchy h = hierarchy_of(scene);
    const SceneRenderer renderer(scene, h);
    Oracle oracle(renderer, h);
    const VisibilityTruth truth = oracle.see(eye(), size, size);
    // The box's front faces show through the glass (its other leaves may hold back faces alone).
    EXPECT_TRUE(holds_any(truth.visible, leaves_of(h, box_mesh))) << "the box behind the glass is not seen";
    EXPECT_TRUE(holds_any(truth.visible, leaves_of(h, glass_mesh))) << "the glass is not seen";
}

TEST(SeeThrough, EveryConservativeStrategyDrawsWhatShowsThroughASeeThroughMesh)
{
    gl::OffscreenContext ctx(size, size);
    frame_state();
    const SceneSetup setup(glass_before_box(), leaves_of_12_triangles(), "glass before box");
    const Scene &scene = setup.scene();
    const Hierarchy &h = setup.hierarchy();
    const SceneRenderer renderer(scene, h);
    const std::vector<std::uint32_t> box_leaves = leaves_of(h, box_mesh), glass_leaves = leaves_of(h, glass_mesh);
    ASSERT_FALSE(box_leaves.empty());
    ASSERT_FALSE(glass_leaves.empty());
    for (std::uint32_t b : box_leaves)
        ASSERT_FALSE(std::count(glass_leaves.begin(), glass_leaves.end(), b)) << "a leaf holds glass and box";
    const Camera camera = eye();

    // The box shows through the glass: the unculled frame differs from the
    // glass alone there.
    {
        const Scene glass_only = glass_before_box(false);
        const Hierarchy gh = hierarchy_of(glass_only);
        const SceneRenderer glass_renderer(glass_only, gh);
        draw_unculled_after(glass_renderer, gh, camera, {});
        const std::vector<std::uint8_t> glass = middle(ctx.pixels());
        ASSERT_NE(glass, std::vector<std::uint8_t>(4, 0)) << "the glass is not drawn";
        draw_unculled_after(renderer, h, camera, {});
        EXPECT_NE(middle(ctx.pixels()), glass) << "the box does not show through the glass";
    }

    // A minimum-occluder-set database made here, from the eye (heading 3 looks down -z).
    std::string database;
    {
        OccluderGrid grid;
        grid.points = {1, 1, 1};
        grid.directions = 4;
        grid.origin = camera.position;
        grid.spacing = glm::vec3(1.0f);
        PreprocessOptions pre;
        pre.stacks.resolution = size / pre.stacks.map_divisor;
        pre.stacks.min_occludee_triangles = 4;
        pre.stacks.min_occluder_pixels = 1;
        OccluderDatabase db = occluder_database_for(h, grid, camera, pre);
        for (std::uint32_t v = 0; v < db.grid.view_count(); ++v)
            db.views[v] = select_occluders_for_view(renderer, h, db.grid.view_camera(v, camera), pre);
        database = ::testing::TempDir() + "occu-see-through-" + std::to_string(getpid()) + ".db";
        db.save(database);
        frame_state();
    }

    // Every conservative strategy and test variant, in batches of one and
    // of its own, through the measurement session.
    MeasurementSession session(setup, ctx, integration::checking_session_options());
    std::set<std::string> labels;
    std::size_t served = 0, refused = 0;
    for (const StrategyTestVariant &declared : integration::conservative_test_variants()) {
        StrategyTestVariant one_at_a_time = declared;
        one_at_a_time.in_batches_of(1);
        for (const StrategyTestVariant &v : {declared, one_at_a_time}) {
            if (!labels.insert(integration::variant_label(v)).second)
                continue;
            try {
                integration::add_variant(session, v, {"database=" + database});
                ++served;
            } catch (const std::invalid_argument &e) {
                // Refusing a scene is allowed, with a reason.
                EXPECT_GT(std::string(e.what()).size(), 10u) << v.spec << " refused without a reason";
                std::printf("%s refuses the scene: %s\n", integration::variant_label(v).c_str(), e.what());
                ++refused;
            }
        }
    }
    std::size_t judged = 0;
    session.measure(0, camera, [&](const SessionStrategy &s, const StrategyFrame &f) {
        SCOPED_TRACE(s.label);
        ++judged;
        EXPECT_TRUE(f.pixels_checked);
        const std::vector<std::uint32_t> &drawn = f.stats.drawn;
        EXPECT_TRUE(holds_any(drawn, box_leaves)) << "culled the box behind the glass; drawn:" << listed(drawn);
        for (std::uint32_t leaf : box_leaves)
            if (std::count(f.frame->truth->visible.begin(), f.frame->truth->visible.end(), leaf)) {
                EXPECT_TRUE(std::count(drawn.begin(), drawn.end(), leaf))
                    << "culled box leaf " << leaf << ", seen through the glass";
            }
        // Lost pixels against the unculled frame, as the demos count them
        // (evaluation/lost_pixels.h).
        EXPECT_EQ(f.loss.lost, 0u) << "drawn:" << listed(drawn);
    });
    std::remove(database.c_str());
    EXPECT_EQ(judged, served);
    EXPECT_GT(served, 20u) << "most strategies should serve a scene of two meshes (" << refused << " refused)";
}
