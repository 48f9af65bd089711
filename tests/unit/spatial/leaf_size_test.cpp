// SPDX-License-Identifier: MIT
// The leaf size chosen per scene (HierarchyOptions::max_leaf_triangles =
// auto_leaf_triangles): the power of two whose leaf count is nearest
// auto_leaf_count_target by ratio.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "scene/city.h"
#include "spatial/hierarchy.h"

using namespace occu;

namespace {

// `count` small triangles in a row along x, one metre apart: the octree's
// octants split a row in halves (every centroid on the centre's side in y
// and z), so a row of count = n * 2^k triangles ends in exactly
// count / size leaves of at most `size`, for sizes 2^k / 2^j that divide it.
Scene row_of_triangles(std::size_t count)
{
    Scene s;
    Mesh m;
    for (std::size_t i = 0; i < count; ++i) {
        const auto x = float(i);
        const auto base = std::uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), {{x, 0, 0}, {x + 0.5f, 0, 0}, {x, 1, 0}});
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
    }
    s.meshes.push_back(std::move(m));
    s.update_bounds();
    return s;
}

Hierarchy build(const Scene &s, std::uint32_t leaf_triangles)
{
    HierarchyOptions o;
    o.max_leaf_triangles = leaf_triangles;
    return Hierarchy::build(s, o);
}

void expect_same(const Hierarchy &a, const Hierarchy &b)
{
    EXPECT_EQ(a.fingerprint(), b.fingerprint());
    EXPECT_EQ(a.max_leaf_triangles(), b.max_leaf_triangles());
    ASSERT_EQ(a.nodes().size(), b.nodes().size());
    for (std::size_t n = 0; n < a.nodes().size(); ++n) {
        EXPECT_EQ(a.nodes()[n].first_triangle, b.nodes()[n].first_triangle) << n;
        EXPECT_EQ(a.nodes()[n].triangle_count, b.nodes()[n].triangle_count) << n;
        EXPECT_EQ(a.nodes()[n].first_child, b.nodes()[n].first_child) << n;
        EXPECT_EQ(a.nodes()[n].child_count, b.nodes()[n].child_count) << n;
    }
    ASSERT_EQ(a.triangles().size(), b.triangles().size());
    for (std::size_t t = 0; t < a.triangles().size(); ++t) {
        EXPECT_EQ(a.triangles()[t].mesh, b.triangles()[t].mesh);
        EXPECT_EQ(a.triangles()[t].first_index, b.triangles()[t].first_index);
    }
}

}  // namespace

TEST(LeafSize, CountsPerSizeOfARowAreItsTrianglesOverTheSize)
{
    const Scene s = row_of_triangles(64 * 1024);
    const auto counts = leaf_counts_by_size(s);
    ASSERT_EQ(counts.size(), 5u);
    std::uint32_t size = 64;
    for (const auto &[built, leaves] : counts) {
        EXPECT_EQ(built, size);
        EXPECT_EQ(leaves, 64u * 1024u / size) << size;
        EXPECT_EQ(leaves, build(s, size).leaf_count()) << size;
        size *= 2;
    }
}

// The counts come from one build at the smallest size: they must be what
// a build at each size makes on a scene the octree does not split evenly.
TEST(LeafSize, CountsPerSizeAreThoseOfTheHierarchiesBuiltAtEachSize)
{
    CityOptions o;
    o.blocks_x = o.blocks_z = 6;
    const Scene city = generate_city(o);
    for (const auto &[size, leaves] : leaf_counts_by_size(city))
        EXPECT_EQ(leaves, build(city, size).leaf_count()) << size;
}

TEST(LeafSize, TheSizeChosenHasTheLeafCountNearestTheTargetByRatio)
{
    const std::size_t t = auto_leaf_count_target;
    // 1.4 times the target at 128 and 0.7 times at 256: 128 is nearer by
    // ratio (a difference would say 256).
    EXPECT_EQ(size_nearest_leaf_count_target({{64, t * 28 / 10}, {128, t * 14 / 10}, {256, t * 7 / 10}}), 128u);
    // 1.5 and 0.75 times: 256 is nearer either way.
    EXPECT_EQ(size_nearest_leaf_count_target({{64, t * 3}, {128, t * 15 / 10}, {256, t * 75 / 100}}), 256u);
    // A tie goes to the larger size (fewer leaves to test).
    EXPECT_EQ(size_nearest_leaf_count_target({{512, t * 2}, {1024, t / 2}}), 1024u);
    // Beyond the ends: few leaves at every size take the smallest, many
    // leaves at every size the largest.
    EXPECT_EQ(size_nearest_leaf_count_target({{64, 12}, {128, 6}, {256, 3}, {512, 1}, {1024, 1}}), 64u);
    EXPECT_EQ(size_nearest_leaf_count_target({{64, t * 64}, {128, t * 32}, {256, t * 16}, {512, t * 8}, {1024, t * 4}}),
              1024u);
    EXPECT_EQ(size_nearest_leaf_count_target({}), auto_leaf_triangles_max);
}

TEST(LeafSize, AutoTakesTheSizeWhoseLeafCountIsNearestTheTargetOnRows)
{
    // A row's leaf counts are powers of two: at the chosen size, the one of
    // them nearest the target (ratio 1024 / 800 = 1.28 against
    // 800 / 512 = 1.56 for the next).
    ASSERT_EQ(auto_leaf_count_target, 800u);
    for (std::uint32_t size : {64u, 256u})
        EXPECT_EQ(choose_leaf_triangles(row_of_triangles(1024 * size)), size) << size;
    EXPECT_EQ(choose_leaf_triangles(row_of_triangles(1024 * 1024 / 2)), 512u);
    // 1,000 triangles: 16 leaves at most, at 64.
    EXPECT_EQ(choose_leaf_triangles(row_of_triangles(1000)), 64u);
}

TEST(LeafSize, AutoBuildsTheHierarchyOfTheSizeItChose)
{
    const Scene row = row_of_triangles(auto_leaf_count_target * 256);
    const Hierarchy chosen = build(row, auto_leaf_triangles);
    EXPECT_EQ(chosen.max_leaf_triangles(), 256u);
    expect_same(chosen, build(row, 256));

    CityOptions o;
    o.blocks_x = o.blocks_z = 6;
    const Scene city = generate_city(o);
    const Hierarchy automatic = build(city, auto_leaf_triangles);
    EXPECT_EQ(automatic.max_leaf_triangles(), choose_leaf_triangles(city));
    expect_same(automatic, build(city, automatic.max_leaf_triangles()));
}

TEST(LeafSize, OptionTakesAutoOrAPositiveIntegerAndNamesItselfOtherwise)
{
    EXPECT_EQ(leaf_triangles_option("--leaf-triangles", "auto"), auto_leaf_triangles);
    EXPECT_EQ(leaf_triangles_option("--leaf-triangles", "512"), 512u);
    EXPECT_EQ(leaf_triangles_text(auto_leaf_triangles), "auto");
    EXPECT_EQ(leaf_triangles_text(512), "512");
    for (const char *bad : {"0", "-4", "", "Auto", "12x", "2000000"}) {
        try {
            leaf_triangles_option("--leaf-triangles", bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const std::invalid_argument &e) {
            EXPECT_NE(std::string(e.what()).find("--leaf-triangles"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(std::string("'") + bad + "'"), std::string::npos) << e.what();
        }
    }
}
