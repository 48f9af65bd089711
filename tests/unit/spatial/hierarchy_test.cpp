// SPDX-License-Identifier: MIT
#include "spatial/hierarchy.h"

#include <gtest/gtest.h>

#include <limits>
#include <set>
#include <stdexcept>

#include "scene/city.h"

using namespace occu;

namespace {
Scene small_city()
{
    CityOptions o;
    o.blocks_x = o.blocks_z = 3;
    return generate_city(o);
}

Aabb triangle_box(const Scene &s, const TriangleRef &t)
{
    Aabb b;
    for (int k = 0; k < 3; ++k)
        b.expand(s.meshes[t.mesh].positions[s.meshes[t.mesh].indices[t.first_index + k]]);
    return b;
}
}  // namespace

TEST(Hierarchy, EveryTriangleInExactlyOneLeafWithinItsBounds)
{
    const Scene s = small_city();
    const Hierarchy h = Hierarchy::build(s);
    ASSERT_EQ(h.triangles().size(), s.triangle_count());
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    std::size_t in_leaves = 0;
    for (const HierarchyNode &n : h.nodes()) {
        if (!n.leaf())
            continue;
        EXPECT_LE(n.triangle_count, 256u);
        in_leaves += n.triangle_count;
        for (std::uint32_t i = 0; i < n.triangle_count; ++i) {
            const TriangleRef &t = h.triangles()[n.first_triangle + i];
            EXPECT_TRUE(seen.insert({t.mesh, t.first_index}).second);
            const Aabb b = triangle_box(s, t);
            EXPECT_TRUE(n.bounds.contains(b.min) && n.bounds.contains(b.max));
        }
    }
    EXPECT_EQ(in_leaves, s.triangle_count());
    EXPECT_GT(h.leaf_count(), s.triangle_count() / 256);
}

TEST(Hierarchy, ParentsBoundTheirChildren)
{
    const Hierarchy h = Hierarchy::build(small_city());
    for (const HierarchyNode &n : h.nodes())
        for (std::uint32_t c = 0; c < n.child_count; ++c) {
            const HierarchyNode &child = h.nodes()[n.first_child + c];
            EXPECT_TRUE(n.bounds.contains(child.bounds.min) && n.bounds.contains(child.bounds.max));
            EXPECT_EQ(child.depth, n.depth + 1);
        }
}

TEST(Hierarchy, LeafSizeIsAKnob)
{
    const Scene s = small_city();
    HierarchyOptions o;
    o.max_leaf_triangles = 64;
    const Hierarchy fine = Hierarchy::build(s, o);
    const Hierarchy coarse = Hierarchy::build(s);
    EXPECT_GT(fine.leaf_count(), coarse.leaf_count());
    for (const HierarchyNode &n : fine.nodes()) {
        if (n.leaf()) {
            EXPECT_LE(n.triangle_count, 64u);
        }
    }
}

TEST(Hierarchy, CoincidentTrianglesEndInOneLeafInsteadOfRecursingForever)
{
    Scene s;
    Mesh m;
    for (int i = 0; i < 1000; ++i)
        append_box(m, Aabb::of({0, 0, 0}, {1, 1, 1}));
    s.meshes.push_back(m);
    s.update_bounds();
    const Hierarchy h = Hierarchy::build(s);
    EXPECT_EQ(h.triangles().size(), 12000u);
    EXPECT_LE(h.nodes().size(), 64u);
}

// A NaN coordinate makes every comparison of the octree's split false, and
// std::nth_element with such an order is undefined: the hierarchy refuses
// the scene instead of building over it.
TEST(Hierarchy, RefusesASceneWithAVertexThatIsNotFinite)
{
    Scene s;
    Mesh m;
    for (int i = 0; i < 100; ++i)
        append_box(m, Aabb::of({float(i), 0, 0}, {float(i) + 0.5f, 1, 1}));
    m.positions[40].x = std::numeric_limits<float>::quiet_NaN();
    s.meshes.push_back(m);
    s.update_bounds();
    HierarchyOptions o;
    o.max_leaf_triangles = 8;
    EXPECT_THROW(Hierarchy::build(s, o), std::runtime_error);
}

// A see-through mesh (Mesh::occluder false) shares leaves with occluders:
// each leaf lists its occluders first, so that whatever draws or rasterizes
// occluders takes a prefix, and the fingerprint tells the scenes apart
// (databases of occluders made for one do not serve the other).
TEST(Hierarchy, LeavesListTheirOccludersBeforeTheirSeeThroughTriangles)
{
    Scene s;
    s.meshes.resize(3);
    append_box(s.meshes[0], Aabb::of({0, 0, 0}, {1, 1, 1}));
    append_box(s.meshes[1], Aabb::of({0.2f, 0.2f, 0.2f}, {0.8f, 0.8f, 0.8f}));
    append_box(s.meshes[2], Aabb::of({0.1f, 0.1f, 0.1f}, {0.9f, 0.9f, 0.9f}));
    s.meshes[0].occluder = false;   // glass around two opaque boxes, listed first
    s.update_bounds();
    const Hierarchy h = Hierarchy::build(s);   // 36 triangles: one leaf
    ASSERT_EQ(h.leaf_count(), 1u);
    const HierarchyNode &leaf = h.root();
    EXPECT_EQ(leaf.triangle_count, 36u);
    EXPECT_EQ(leaf.occluder_triangles, 24u);
    for (std::uint32_t i = 0; i < leaf.triangle_count; ++i)
        EXPECT_EQ(s.meshes[h.triangles()[leaf.first_triangle + i].mesh].occluder, i < leaf.occluder_triangles) << i;

    Scene opaque = s;
    opaque.meshes[0].occluder = true;
    const Hierarchy o = Hierarchy::build(opaque);
    EXPECT_EQ(o.root().occluder_triangles, 36u);
    EXPECT_NE(o.fingerprint(), h.fingerprint());
    EXPECT_EQ(o.fingerprint(), Hierarchy::build(opaque).fingerprint());
}
