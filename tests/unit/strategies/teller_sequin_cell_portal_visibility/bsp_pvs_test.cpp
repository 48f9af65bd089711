// SPDX-License-Identifier: MIT
// bsp-pvs (strategies/teller_sequin_cell_portal_visibility/family.h) on a
// hand-made level: four rooms in a row along x, one BSP leaf and cluster
// each, a solid leaf before the first, and visibility data in which each
// room sees its neighbours only. Checks the eye's cluster by descending
// the tree, the visibility bits, faces listed by two leaves, brush-entity
// faces, world faces in no cluster, the fallbacks (an eye in a solid leaf,
// a level without visibility data) and the refusal of a scene that is no
// level.
#include "strategies/teller_sequin_cell_portal_visibility/family.h"

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <set>
#include <stdexcept>

#include "gl/offscreen_context.h"
#include "render/scene_renderer.h"
#include "scene/level.h"
#include "spatial/hierarchy.h"

using namespace occu;

namespace {

// Faces: 0-3 the far walls of rooms 0-3; 4 a wall crossing the plane
// between rooms 2 and 3 (listed by both leaves); 5 a brush entity's (a
// door, model 1: listed by no leaf); 6 a world face no leaf lists.
constexpr int face_count = 7;
constexpr int crossing_face = 4, brush_face = 5, unlisted_face = 6;

// Room r spans x in [10 r, 10 r + 10] metres; the solid leaf x < 0.
struct TestLevel {
    explicit TestLevel(bool with_visibility = true)
    {
        auto level = std::make_shared<Level>();
        Mesh mesh;
        mesh.name = "wall";
        // A small wall (two triangles) facing -x at x, centred at (y, z).
        auto wall = [&](float x, float z) {
            const std::uint32_t base = std::uint32_t(mesh.positions.size()), first = std::uint32_t(mesh.indices.size());
            for (const glm::vec3 &p : {glm::vec3(x, -0.5f, z - 0.5f), glm::vec3(x, -0.5f, z + 0.5f),
                                       glm::vec3(x, 0.5f, z + 0.5f), glm::vec3(x, 0.5f, z - 0.5f)}) {
                mesh.positions.push_back(p);
                mesh.normals.push_back({-1, 0, 0});
            }
            for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u})
                mesh.indices.push_back(base + i);
            Level::Face f{1, 0, 0, 0, first, 6};
            level->faces.push_back(f);
        };
        for (int r = 0; r < 4; ++r)
            wall(10.0f * float(r) + 8.0f, 0.0f);
        wall(30.0f, 3.0f);                       // crossing: on the plane x = 30
        wall(38.0f, -3.0f);                      // the brush entity's, in room 3
        wall(18.0f, -3.0f);                      // the unlisted world face, in room 1
        level->faces[brush_face].model = 1;
        mesh.update_bounds();
        scene.meshes.push_back(mesh);
        scene.update_bounds();

        // Planes x = 10, 0, 20, 30 (front: x greater).
        level->planes = {{{1, 0, 0}, 10}, {{1, 0, 0}, 0}, {{1, 0, 0}, 20}, {{1, 0, 0}, 30}};
        // Node 0 splits at x = 10; node 1 (x < 10) at 0: room 0 or solid;
        // node 2 (x > 10) at 20: room 1 or node 3, which splits at 30.
        // A child < 0 is leaf -(child + 1).
        level->nodes = {{0, {2, 1}, scene.bounds}, {1, {-1, -5}, scene.bounds}, {2, {3, -2}, scene.bounds},
                        {3, {-4, -3}, scene.bounds}};
        level->leaves = {{0, 0, scene.bounds, 0, 1}, {1, 0, scene.bounds, 1, 1}, {2, 0, scene.bounds, 2, 2},
                         {3, 0, scene.bounds, 4, 2}, {-1, 0, scene.bounds, 6, 0}};
        level->leaf_faces = {0, 1, 2, crossing_face, 3, crossing_face};
        if (with_visibility) {
            // Row c: the clusters c sees (bit k of byte 0: cluster k).
            level->cluster_count = 4;
            level->bytes_per_cluster = 1;
            level->visibility = {0b0011, 0b0111, 0b1110, 0b1100};
        }
        scene.level = level;
        hierarchy.emplace(Hierarchy::build(scene, HierarchyOptions{2, 20}));
        renderer.emplace(scene, *hierarchy);
    }

    // The faces of hierarchy leaf `node` (by their triangles' indices).
    std::set<int> faces_of(std::uint32_t node) const
    {
        std::set<int> faces;
        const HierarchyNode &n = hierarchy->nodes()[node];
        for (std::uint32_t t = n.first_triangle; t < n.first_triangle + n.triangle_count; ++t)
            faces.insert(int(hierarchy->triangles()[t].first_index / 6));
        return faces;
    }

    gl::OffscreenContext ctx{8, 8};
    Scene scene;
    std::optional<Hierarchy> hierarchy;
    std::optional<SceneRenderer> renderer;
};

// The eye at x looking along +x, wide enough to see every wall ahead.
Camera eye_at(float x)
{
    Camera c;
    c.position = {x, 0.0f, 0.0f};
    c.target = {x + 1.0f, 0.0f, 0.0f};
    c.fovy_degrees = 120.0f;
    c.near_plane = 0.1f;
    return c;
}

// bsp-pvs's answer for every hierarchy leaf seen from `camera`, as the set
// of faces in leaves answered visible; every leaf that is not visible must
// be occluded (in the frustum) or view-culled (outside it).
std::set<int> drawn_faces(const TestLevel &t, const Camera &camera, const std::string &strategy = "bsp-pvs")
{
    const StrategyContext context{t.scene, *t.hierarchy, *t.renderer};
    const Strategy s = make_strategy(strategy, context);
    const Frame frame(camera, 8, 8);
    s.culler->begin_frame(frame);
    std::vector<NodeTest> tests;
    const auto &nodes = t.hierarchy->nodes();
    for (std::uint32_t n = 0; n < nodes.size(); ++n)
        if (nodes[n].leaf())
            tests.push_back({n, nodes[n].bounds, true});
    s.culler->test(tests);
    std::set<int> drawn;
    for (const NodeTest &test : tests) {
        const bool outside = frame.frustum.classify(test.box) == Frustum::Side::outside;
        if (test.result == Visibility::visible) {
            EXPECT_FALSE(outside) << "node " << test.node;
            for (int f : t.faces_of(test.node))
                drawn.insert(f);
        } else {
            EXPECT_EQ(test.result, outside ? Visibility::view_culled : Visibility::occluded) << "node " << test.node;
        }
    }
    return drawn;
}

}  // namespace

TEST(BspPvs, EachHierarchyLeafHoldsOneFace)
{
    // The checks below read a leaf's answer as its face's.
    const TestLevel t;
    std::size_t leaves = 0;
    for (std::uint32_t n = 0; n < t.hierarchy->nodes().size(); ++n)
        if (t.hierarchy->nodes()[n].leaf()) {
            EXPECT_EQ(t.faces_of(n).size(), 1u) << "node " << n;
            ++leaves;
        }
    EXPECT_EQ(leaves, std::size_t(face_count));
}

TEST(BspPvs, EyeClusterByDescendingTheTree)
{
    const TestLevel t;
    const Level &level = *t.scene.level;
    EXPECT_EQ(level.leaf_at({5, 0, 0}), 0);
    EXPECT_EQ(level.leaf_at({15, 0, 0}), 1);
    EXPECT_EQ(level.leaf_at({25, 0, 0}), 2);
    EXPECT_EQ(level.leaf_at({35, 0, 0}), 3);
    EXPECT_EQ(level.leaf_at({-5, 0, 0}), 4);
}

TEST(BspPvs, DrawsTheFacesInLeavesOfClustersTheEyesClusterSees)
{
    const TestLevel t;
    // Room 0 sees rooms 0 and 1: their walls, the brush entity (always
    // drawn); not rooms 2 and 3, nor the wall between them, nor the face no
    // leaf lists.
    EXPECT_EQ(drawn_faces(t, eye_at(1)), (std::set<int>{0, 1, brush_face}));
    // Room 1 sees 0, 1 and 2: the crossing wall lies in leaf 2 too.
    EXPECT_EQ(drawn_faces(t, eye_at(11)), (std::set<int>{1, 2, crossing_face, brush_face}));
    // Room 2 sees 1, 2, 3 (room 0's wall, behind the eye, is view-culled).
    EXPECT_EQ(drawn_faces(t, eye_at(21)), (std::set<int>{2, 3, crossing_face, brush_face}));
    // Room 3 sees 2 and 3: ahead of it, its own wall and the door.
    EXPECT_EQ(drawn_faces(t, eye_at(31)), (std::set<int>{3, brush_face}));
}

TEST(BspPvs, EyeInASolidLeafDrawsEverythingInTheFrustum)
{
    const TestLevel t;
    EXPECT_EQ(drawn_faces(t, eye_at(-5)), (std::set<int>{0, 1, 2, 3, crossing_face, brush_face, unlisted_face}));
}

TEST(BspPvs, LevelWithoutVisibilityDataDrawsEverythingInTheFrustum)
{
    const TestLevel t(false);
    EXPECT_EQ(drawn_faces(t, eye_at(1)), (std::set<int>{0, 1, 2, 3, crossing_face, brush_face, unlisted_face}));
}

TEST(BspPvs, VisibilityBitsAreReadPerCluster)
{
    TestLevel t;
    std::vector<std::uint8_t> &rows = std::const_pointer_cast<Level>(t.scene.level)->visibility;
    // Room 1's row is 0b0111; its bit 3 set, room 3 is visible from room 1.
    rows[1] |= 0b1000;
    EXPECT_EQ(drawn_faces(t, eye_at(11)), (std::set<int>{1, 2, 3, crossing_face, brush_face}));
    // Room 0 seeing itself and room 3 only: the crossing wall shows by leaf 3 alone.
    rows[0] = 0b1001;
    EXPECT_EQ(drawn_faces(t, eye_at(1)), (std::set<int>{0, 3, crossing_face, brush_face}));
}

TEST(BspPvs, TheNoteCountsFramesAndFaces)
{
    const TestLevel t;
    const StrategyContext context{t.scene, *t.hierarchy, *t.renderer};
    const Strategy s = make_strategy("bsp-pvs", context);
    for (float x : {1.0f, -5.0f, 11.0f}) {
        const Frame frame(eye_at(x), 8, 8);
        s.culler->begin_frame(frame);
    }
    const std::string note = s.culler->note();
    EXPECT_NE(note.find("1 of 3 frames with the eye in no cluster"), std::string::npos) << note;
    EXPECT_NE(note.find("2 triangles of brush entities always drawn"), std::string::npos) << note;
    EXPECT_NE(note.find("2 triangles of world faces in no cluster's leaf never drawn"), std::string::npos) << note;
}

TEST(BspPvs, SceneThatIsNoLevelIsRefusedWithTheReason)
{
    gl::OffscreenContext ctx{8, 8};
    Scene scene;
    scene.meshes.emplace_back();
    append_box(scene.meshes[0], Aabb::of({0, 0, 0}, {1, 1, 1}));
    scene.update_bounds();
    const Hierarchy h = Hierarchy::build(scene);
    const SceneRenderer renderer(scene, h);
    const StrategyContext context{scene, h, renderer};
    try {
        make_strategy("bsp-pvs", context);
        ADD_FAILURE() << "bsp-pvs made on a scene without a BSP";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("bsp-pvs needs a Quake III level's BSP tree, clusters and visibility"),
                  std::string::npos)
            << e.what();
    }
}


// In a chain, the next stage tests only what bsp-pvs leaves: vfc then adds
// nothing, and bsp-pvs after vfc answers as alone.
TEST(BspPvs, ChainedWithOtherStrategies)
{
    const TestLevel t;
    for (float x : {1.0f, 11.0f, 21.0f, -5.0f})
        for (const char *chain : {"bsp-pvs+vfc", "vfc+bsp-pvs"})
            EXPECT_EQ(drawn_faces(t, eye_at(x), chain), drawn_faces(t, eye_at(x))) << chain << " at x = " << x;
}
