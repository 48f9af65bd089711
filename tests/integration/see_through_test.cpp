// SPDX-License-Identifier: MIT
// A see-through mesh (Mesh::occluder false: a Quake III level's glass,
// water or fog, scene/quake3_bsp.h) is drawn but hides nothing: what lies
// behind it shows through it in the frame, the oracle counts it visible, no
// strategy culls it, and no preprocessing step makes an occluder of the
// see-through mesh. The scene: a solid block of glass, thick enough for
// occluder skins and covering the whole view of an opaque box behind it,
// and nothing else. Every conservative strategy of the registry must draw
// the box and lose no pixel against the unculled frame; a strategy that
// cannot serve the scene must refuse it with a reason. Runs on the driver
// meson selects with GALLIUM_DRIVER.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "culling/registry.h"
#include "evaluation/lost_pixels.h"
#include "evaluation/oracle.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "occluders/occluder_skins.h"
#include "occluders/skin_occluders.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"
#include "strategies/poon_wang_opacity_maps/occluder_database.h"
#include "strategies/poon_wang_opacity_maps/view_preprocessing.h"
#include "traversal/traversal.h"

#include "frame_comparison.h"

using namespace occu;
using occu::integration::draw_frame;
using occu::integration::DrawnFrame;

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
Hierarchy hierarchy_of(const Scene &scene)
{
    HierarchyOptions options;
    options.max_leaf_triangles = 12;
    return Hierarchy::build(scene, options);
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

// The pixel at the middle of the frame, RGBA8.
std::vector<std::uint8_t> middle(const std::vector<std::uint8_t> &pixels)
{
    const std::size_t i = 4 * (std::size_t(size / 2) * size + size / 2);
    return {pixels.begin() + std::ptrdiff_t(i), pixels.begin() + std::ptrdiff_t(i + 4)};
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
    const Scene scene = glass_before_box();
    const Hierarchy h = hierarchy_of(scene);
    const SceneRenderer renderer(scene, h);
    const std::vector<std::uint32_t> box_leaves = leaves_of(h, box_mesh), glass_leaves = leaves_of(h, glass_mesh);
    ASSERT_FALSE(box_leaves.empty());
    ASSERT_FALSE(glass_leaves.empty());
    for (std::uint32_t b : box_leaves)
        ASSERT_FALSE(std::count(glass_leaves.begin(), glass_leaves.end(), b)) << "a leaf holds glass and box";
    const Camera camera = eye();
    Oracle oracle(renderer, h);
    const VisibilityTruth truth = oracle.see(camera, size, size);
    const Frame frame(camera, size, size, &truth);
    const StrategyContext context{scene, h, renderer};
    const Strategy none = make_strategy("none", context);
    const DrawnFrame unculled = draw_frame(ctx, renderer, h, *none.culler, frame, {});

    // The box shows through the glass: the frame differs from the glass alone there.
    {
        const Scene glass_only = glass_before_box(false);
        const Hierarchy gh = hierarchy_of(glass_only);
        const SceneRenderer glass_renderer(glass_only, gh);
        const StrategyContext glass_context{glass_only, gh, glass_renderer};
        const Strategy glass_none = make_strategy("none", glass_context);
        const DrawnFrame glass = draw_frame(ctx, glass_renderer, gh, *glass_none.culler, Frame(camera, size, size), {});
        ASSERT_NE(middle(glass.pixels), std::vector<std::uint8_t>(4, 0)) << "the glass is not drawn";
        EXPECT_NE(middle(unculled.pixels), middle(glass.pixels)) << "the box does not show through the glass";
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

    std::size_t served = 0, refused = 0;
    for (const std::string &name : strategy_names()) {
        if (!choose_strategy(name).conservative())
            continue;
        SCOPED_TRACE(name);
        std::optional<Strategy> s;
        try {
            s.emplace(make_strategy(name, context, {"database=" + database}));
        } catch (const std::invalid_argument &e) {
            // Refusing a scene is allowed, with a reason.
            EXPECT_GT(std::string(e.what()).size(), 10u) << "refused without a reason";
            std::printf("%s refuses the scene: %s\n", name.c_str(), e.what());
            ++refused;
            continue;
        }
        ++served;
        for (std::size_t batch : {std::size_t(1), std::size_t(16)}) {
            TraversalOptions options;
            options.batch = batch;
            const DrawnFrame culled = draw_frame(ctx, renderer, h, *s->culler, frame, options);
            EXPECT_TRUE(holds_any(culled.leaves, box_leaves))
                << "culled the box behind the glass (batches of " << batch << "); drawn:" << listed(culled.leaves);
            for (std::uint32_t leaf : box_leaves)
                if (std::count(truth.visible.begin(), truth.visible.end(), leaf)) {
                    EXPECT_TRUE(std::count(culled.leaves.begin(), culled.leaves.end(), leaf))
                        << "culled box leaf " << leaf << ", seen through the glass (batches of " << batch << ")";
                }
            // Lost pixels against the unculled frame, as the demos count them
            // (evaluation/lost_pixels.h).
            const PixelLoss loss = count_lost_pixels(renderer, h, camera, culled.leaves, unculled.pixels.data(),
                                                     culled.pixels.data(), std::size_t(size) * size);
            EXPECT_EQ(loss.lost, 0u) << "batches of " << batch << "; drawn:" << listed(culled.leaves);
        }
    }
    std::remove(database.c_str());
    EXPECT_GT(served, 10u) << "most strategies should serve a scene of two meshes (" << refused << " refused)";
}
