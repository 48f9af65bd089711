// SPDX-License-Identifier: MIT
// Collision detection with occlusion tiles (Bartz et al. 1998, section 5,
// figure 7; applications/collision_detection.h): hand-built cases (a wall
// one step ahead, a wall just beyond the step, a pillar in a side tile,
// back faces, a wall behind a backward step) where the GL check and the
// exact CPU test must both give the expected tiles; and random steps in a
// small city where they must agree except where the exact test's own
// explanation (sub-pixel geometry, depth precision) accounts for it.
#include "applications/collision_detection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include "camera/route.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "scene/city.h"

using namespace occu;

namespace {

constexpr int size = 96;   // tiles of 32 x 32 pixels

std::array<bool, collision_tile_count> tiles_of(std::initializer_list<int> colliding)
{
    std::array<bool, collision_tile_count> t{};
    for (int k : colliding)
        t[std::size_t(k)] = true;
    return t;
}

std::array<bool, collision_tile_count> gl_answer(const CollisionResult &r)
{
    std::array<bool, collision_tile_count> t{};
    for (int k = 0; k < collision_tile_count; ++k)
        t[std::size_t(k)] = r.tiles[std::size_t(k)].collides;
    return t;
}

std::string describe(const std::array<bool, collision_tile_count> &t)
{
    std::string s;
    for (int k = 0; k < collision_tile_count; ++k)
        if (t[std::size_t(k)])
            s += std::string(s.empty() ? "" : ", ") + heading_name(k);
    return s.empty() ? "none" : s;
}

// A one-sided quad from a, b, c, d, counter-clockwise seen from the side
// its normal points to.
void append_quad(Mesh &mesh, const glm::vec3 &a, const glm::vec3 &b, const glm::vec3 &c, const glm::vec3 &d)
{
    const glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
    const std::uint32_t first = std::uint32_t(mesh.positions.size());
    for (const glm::vec3 &p : {a, b, c, d}) {
        mesh.positions.push_back(p);
        mesh.normals.push_back(normal);
    }
    for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u})
        mesh.indices.push_back(first + i);
}

// A scene of boxes and quads, the eye at 1.7 m looking down -z.
struct World {
    gl::OffscreenContext ctx{size, size};
    Scene scene;
    std::optional<Hierarchy> hierarchy;
    std::optional<SceneRenderer> renderer;
    std::optional<CollisionCheck> check;
    std::optional<ExactCollisionTest> exact;
    Camera camera;

    World() { scene.meshes.emplace_back(); }
    void box(const glm::vec3 &lo, const glm::vec3 &hi) { append_box(scene.meshes[0], Aabb::of(lo, hi)); }
    void build()
    {
        scene.update_bounds();
        HierarchyOptions ho;
        ho.max_leaf_triangles = 12;
        hierarchy.emplace(Hierarchy::build(scene, ho));
        renderer.emplace(scene, *hierarchy);
        check.emplace(*renderer, *hierarchy);
        exact.emplace(scene, *hierarchy);
        camera.position = {0, 1.7f, 0};
        camera.target = {0, 1.7f, -1};
        camera.near_plane = 0.5f;
        camera.far_plane = 100.0f;
        glViewport(0, 0, size, size);
    }
    // The GL check of a step from `camera` (forward: on the frame drawn
    // first), which must agree with the exact test; returns the tiles.
    std::array<bool, collision_tile_count> step(float length, StepDirection direction = StepDirection::forward)
    {
        draw_collision_frame(*renderer, *hierarchy, camera);
        const CollisionResult r = check->check(camera, length, direction);
        const auto truth = exact->check(camera, length, direction, size, size);
        const auto tiles = heading_tiles({0, 0, size, size});
        for (int k = 0; k < collision_tile_count; ++k)
            EXPECT_EQ(r.tiles[std::size_t(k)].phc, std::uint32_t(tiles[std::size_t(k)].area()))
                << heading_name(k) << ": the far face covers every pixel of its tile once";
        EXPECT_EQ(describe(gl_answer(r)), describe(truth)) << "GL check and exact test";
        return gl_answer(r);
    }
};

}  // namespace

TEST(CollisionTiles, AreFigureSevensSplitFromTheTopLeft)
{
    const auto t = heading_tiles({10, 20, 10 + 512, 20 + 300});
    EXPECT_STREQ(heading_name(0), "straight-up-left");
    EXPECT_STREQ(heading_name(4), "straight");
    EXPECT_STREQ(heading_name(8), "straight-down-right");
    // Row 0 is the top of the screen: the highest window y.
    EXPECT_EQ(t[0], (PixelRect{10, 220, 181, 320}));
    EXPECT_EQ(t[4], (PixelRect{181, 120, 351, 220}));
    EXPECT_EQ(t[8], (PixelRect{351, 20, 522, 120}));
    std::int64_t area = 0;
    for (const PixelRect &r : t)
        area += r.area();
    EXPECT_EQ(area, 512 * 300);
}

TEST(CollisionCheck, WallOneStepAheadFillsTheStraightRow)
{
    // A band at eye height 2 m ahead, wide: at that distance +-0.3 m is
    // +-0.15 in tangent, inside the middle row (+-tan(30)/3 = +-0.19).
    World w;
    w.box({-5, 1.4f, -2.2f}, {5, 2.0f, -2.0f});
    w.build();
    EXPECT_EQ(describe(w.step(3.0f)), describe(tiles_of({3, 4, 5})));
    EXPECT_EQ(describe(w.step(1.9f)), "none") << "the wall lies beyond a shorter step";
}

TEST(CollisionCheck, WallJustBeyondTheStepIsFree)
{
    World w;
    w.box({-50, -50, -3.25f}, {50, 50, -3.05f});
    w.build();
    EXPECT_EQ(describe(w.step(3.0f)), "none");
    EXPECT_EQ(describe(w.step(3.1f)), describe(tiles_of({0, 1, 2, 3, 4, 5, 6, 7, 8})));
}

TEST(CollisionCheck, PillarInASideTileCollidesThereOnly)
{
    // 0.3..0.4 in tangent to the right (the right column starts at 0.19),
    // +-0.1 up and down: the straight-right tile alone.
    World w;
    w.box({0.6f, 1.5f, -2.2f}, {0.8f, 1.9f, -2.0f});
    w.build();
    EXPECT_EQ(describe(w.step(2.5f)), describe(tiles_of({5})));
}

// A quad facing the eye at view depth 2 over the window pixels x0..x1,
// y0..y1 (fractions allowed) of the 96 x 96 view from World's camera.
void window_quad(World &w, double x0, double x1, double y0, double y1)
{
    const double t = std::tan(glm::radians(30.0)), depth = 2.0;
    auto wx = [&](double x) { return float((2.0 * x / size - 1.0) * t * depth); };
    auto wy = [&](double y) { return float(1.7 + (2.0 * y / size - 1.0) * t * depth); };
    append_quad(w.scene.meshes[0], {wx(x0), wy(y0), -2}, {wx(x1), wy(y0), -2}, {wx(x1), wy(y1), -2},
                {wx(x0), wy(y1), -2});
}

TEST(CollisionCheck, TileEdgesAreThePixelEdges)
{
    // A strip 0.2 to 0.8 pixels right of the edge between straight and
    // straight-right (x = 64), over the pixel centres x = 64.5: both
    // methods put it in straight-right alone.
    World w;
    window_quad(w, 64.2, 64.8, 40, 56);
    w.build();
    EXPECT_EQ(describe(w.step(3.0f)), describe(tiles_of({5})));
    const CollisionResult r = w.check->check(w.camera, 3.0f, StepDirection::forward);
    EXPECT_EQ(r.tiles[5].phc - r.tiles[5].nohc, 16u) << "one column of 16 pixels";
}

TEST(CollisionCheck, GeometryBetweenPixelCentresIsSubPixel)
{
    // A strip between the pixel centres 63.5 and 64.5, in straight: inside
    // the exact volume, invisible to the GL, and explain() says why.
    World w;
    window_quad(w, 63.6, 63.9, 40, 56);
    w.build();
    draw_collision_frame(*w.renderer, *w.hierarchy, w.camera);
    const CollisionResult gl = w.check->check(w.camera, 3.0f, StepDirection::forward);
    const auto truth = w.exact->check(w.camera, 3.0f, StepDirection::forward, size, size);
    EXPECT_EQ(describe(gl_answer(gl)), "none");
    EXPECT_EQ(describe(truth), describe(tiles_of({4})));
    const auto why = w.exact->explain(w.camera, 3.0f, StepDirection::forward, size, size, gl, truth);
    for (int k = 0; k < collision_tile_count; ++k)
        EXPECT_EQ(agreement_name(why[std::size_t(k)]), std::string(k == 4 ? "sub-pixel" : "agree")) << heading_name(k);
}

TEST(CollisionCheck, BackFacesCollide)
{
    // One quad 2 m ahead, facing away from the eye (its front side is -z).
    World w;
    append_quad(w.scene.meshes[0], {-50, -50, -2}, {-50, 50, -2}, {50, 50, -2}, {50, -50, -2});
    w.build();
    const auto all = describe(tiles_of({0, 1, 2, 3, 4, 5, 6, 7, 8}));
    EXPECT_EQ(describe(w.step(3.0f)), all);

    // A frame drawn with back faces culled, as walkthrough draws it, does
    // not hold the wall: it is a back face indeed, and the frame must keep
    // back faces (draw_collision_frame) for the check to see it.
    glEnable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl::load_camera(w.camera);
    for (std::uint32_t n = 0; n < w.hierarchy->nodes().size(); ++n)
        if (w.hierarchy->nodes()[n].leaf())
            w.renderer->draw_leaf(n);
    EXPECT_FALSE(w.check->check(w.camera, 3.0f, StepDirection::forward).any());

    // The caller's culling does not cull the check's far face: "backface
    // culling must be disabled" (section 5) is the check's business.
    draw_collision_frame(*w.renderer, *w.hierarchy, w.camera);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT_AND_BACK);
    EXPECT_EQ(describe(gl_answer(w.check->check(w.camera, 3.0f, StepDirection::forward))), all);
    GLint cull = 0;
    glGetIntegerv(GL_CULL_FACE_MODE, &cull);
    EXPECT_EQ(cull, GL_FRONT_AND_BACK) << "the caller's state comes back";
    EXPECT_TRUE(glIsEnabled(GL_CULL_FACE));
    glCullFace(GL_BACK);
    glDisable(GL_CULL_FACE);
}

TEST(CollisionCheck, InsideABoxEveryTileCollides)
{
    // Every face of the box is a back face from inside it.
    World w;
    w.box({-1.5f, 0, -1.5f}, {1.5f, 3, 1.5f});
    w.build();
    const auto all = describe(tiles_of({0, 1, 2, 3, 4, 5, 6, 7, 8}));
    EXPECT_EQ(describe(w.step(2.5f)), all);
    EXPECT_EQ(describe(w.step(2.5f, StepDirection::backward)), all);
}

TEST(CollisionCheck, BackwardStepSeesTheWallBehindInASecondPass)
{
    // A wall 2 m behind, nothing ahead, and a pillar behind and to the
    // walker's right, which the turned view sees on its left.
    World w;
    w.box({-50, -50, 1.8f}, {50, 50, 2.0f});
    w.box({0.35f, 1.55f, 1.0f}, {0.5f, 1.85f, 1.2f});
    w.build();
    EXPECT_EQ(describe(w.step(3.0f)), "none");
    const auto all = describe(tiles_of({0, 1, 2, 3, 4, 5, 6, 7, 8}));
    EXPECT_EQ(describe(w.step(2.5f, StepDirection::backward)), all);
    EXPECT_EQ(describe(w.step(1.5f, StepDirection::backward)), describe(tiles_of({3})));

    // The second pass draws into the check's own framebuffer: the caller's
    // frame, viewport and matrices stay.
    draw_collision_frame(*w.renderer, *w.hierarchy, w.camera);
    glFinish();
    const std::vector<std::uint8_t> before(w.ctx.pixels(), w.ctx.pixels() + size * size * 4);
    GLfloat modelview_before[16], modelview_after[16];
    glGetFloatv(GL_MODELVIEW_MATRIX, modelview_before);
    w.check->check(w.camera, 2.5f, StepDirection::backward);
    glFinish();
    EXPECT_EQ(before, std::vector<std::uint8_t>(w.ctx.pixels(), w.ctx.pixels() + size * size * 4));
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    EXPECT_EQ(viewport[2], size);
    EXPECT_EQ(viewport[3], size);
    glGetFloatv(GL_MODELVIEW_MATRIX, modelview_after);
    EXPECT_TRUE(std::equal(modelview_before, modelview_before + 16, modelview_after));
    EXPECT_LE(w.check->last_pass_leaves(), w.hierarchy->leaf_count());
}

TEST(CollisionCheck, StepsWithoutAVolumeAreRefused)
{
    World w;
    w.box({-1, 0, -3}, {1, 3, -2});
    w.build();
    for (float bad : {0.4f, 0.5f, 100.0f, 1e9f, std::nanf(""), INFINITY}) {
        EXPECT_THROW(w.check->check(w.camera, bad, StepDirection::forward), std::invalid_argument) << bad;
        EXPECT_THROW(w.check->check(w.camera, bad, StepDirection::backward), std::invalid_argument) << bad;
        EXPECT_THROW(w.exact->check(w.camera, bad, StepDirection::forward, size, size), std::invalid_argument) << bad;
    }
}

// Random steps in a 2 x 2 block city: eyes anywhere in its bounds up to
// 20 m (in streets, courtyards and inside buildings), looking in any
// heading within 30 degrees of the horizon, steps of 0.6 to 12 m, a third
// of them backward. The GL check must count in its own pass exactly what
// it counts on the frame (the leaves beyond reach change nothing); and it
// must agree with the exact test in every tile where the exact test's
// explanation does not name sub-pixel geometry or depth precision (a tile
// it cannot explain fails). Disagreements stay rare, and both answers
// occur often, so the comparison means something.
TEST(CollisionCheck, AgreesWithTheExactTestOnRandomStepsInASmallCity)
{
    constexpr int view = 120;   // tiles of 40 x 40
    gl::OffscreenContext ctx(view, view);
    CityOptions city;
    city.blocks_x = city.blocks_z = 2;
    const Scene scene = generate_city(city);
    const Hierarchy hierarchy = Hierarchy::build(scene);
    SceneRenderer renderer(scene, hierarchy);
    CollisionCheck check(renderer, hierarchy);
    const ExactCollisionTest exact(scene, hierarchy);
    glViewport(0, 0, view, view);

    std::mt19937 random(17);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const Camera lens = street_level_lens(scene.bounds, 1.0f);
    int steps = 0, tiles = 0, positives = 0, negatives = 0, explained = 0, sub_pixel = 0, precision = 0;
    int flips = 0, caught = 0;
    for (; steps < 300; ++steps) {
        Camera camera = lens;
        camera.position = {scene.bounds.min.x + unit(random) * scene.bounds.extent().x, 0.3f + 19.7f * unit(random),
                           scene.bounds.min.z + unit(random) * scene.bounds.extent().z};
        const float heading = 6.2831853f * unit(random), pitch = glm::radians(60.0f * unit(random) - 30.0f);
        camera.target = camera.position + glm::vec3(std::cos(pitch) * std::cos(heading), std::sin(pitch),
                                                    std::cos(pitch) * std::sin(heading));
        const float length = 0.6f + 11.4f * unit(random);
        const StepDirection direction = steps % 3 == 2 ? StepDirection::backward : StepDirection::forward;

        draw_collision_frame(renderer, hierarchy, camera);
        const CollisionResult gl = check.check(camera, length, direction);
        if (direction == StepDirection::forward) {
            const CollisionResult own = check.check_own_pass(camera, length, direction);
            for (int k = 0; k < collision_tile_count; ++k) {
                const TileCheck &o = own.tiles[std::size_t(k)], &f = gl.tiles[std::size_t(k)];
                EXPECT_EQ(o.nohc, f.nohc) << "step " << steps << ", " << heading_name(k);
                EXPECT_EQ(o.phc, f.phc) << "step " << steps << ", " << heading_name(k);
            }
        }
        const auto truth = exact.check(camera, length, direction, view, view);
        const auto why = exact.explain(camera, length, direction, view, view, gl, truth);
        for (int k = 0; k < collision_tile_count; ++k) {
            ++tiles;
            (truth[std::size_t(k)] ? positives : negatives) += 1;
            const Agreement a = why[std::size_t(k)];
            EXPECT_NE(a, Agreement::unexplained)
                << "step " << steps << " (" << step_direction_name(direction) << ", " << length << " m from "
                << camera.position.x << ", " << camera.position.y << ", " << camera.position.z << "), "
                << heading_name(k) << ": GL " << (gl.tiles[std::size_t(k)].collides ? "collision" : "free") << " (NOHC "
                << gl.tiles[std::size_t(k)].nohc << ", PHC " << gl.tiles[std::size_t(k)].phc << "), exact "
                << (truth[std::size_t(k)] ? "collision" : "free");
            if (a == Agreement::sub_pixel || a == Agreement::depth_precision)
                ++explained;
            sub_pixel += a == Agreement::sub_pixel;
            precision += a == Agreement::depth_precision;
        }
        // The explanation must not excuse a wrong answer: with each tile
        // where both agree flipped in the GL's answer, explain() has to call
        // it unexplained (a collision the GL saw is seen at pixel centres
        // by the ray cast; a free tile has nothing within the tolerance).
        // Only geometry within the depth tolerance of the far or near
        // plane, in a tile where the two agree, could excuse a flip; this
        // sample has none, so every flip must be caught.
        CollisionResult flipped = gl;
        for (int k = 0; k < collision_tile_count; ++k)
            if (why[std::size_t(k)] == Agreement::agree)
                flipped.tiles[std::size_t(k)].collides = !flipped.tiles[std::size_t(k)].collides;
        const auto why_flipped = exact.explain(camera, length, direction, view, view, flipped, truth);
        for (int k = 0; k < collision_tile_count; ++k)
            if (why[std::size_t(k)] == Agreement::agree) {
                ++flips;
                caught += why_flipped[std::size_t(k)] == Agreement::unexplained;
            }
    }
    RecordProperty("tiles", tiles);
    RecordProperty("sub_pixel", sub_pixel);
    RecordProperty("depth_precision", precision);
    std::printf("%d steps, %d tiles: %d collide, %d free; explained disagreements: %d sub-pixel, %d depth precision; "
                "%d of %d flipped answers caught\n",
                steps, tiles, positives, negatives, sub_pixel, precision, caught, flips);
    EXPECT_GE(positives, tiles / 10);
    EXPECT_GE(negatives, tiles / 10);
    EXPECT_LE(explained, tiles / 50) << "explained disagreements should stay rare";
    EXPECT_EQ(caught, flips) << "explain() excuses wrong answers";
}
