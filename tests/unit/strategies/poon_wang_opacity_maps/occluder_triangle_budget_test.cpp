// SPDX-License-Identifier: MIT
// A budget of occluders in triangles (selection.h,
// first_leaves_within_triangles) against a brute-force search from the
// definition, not from the implementation's loop: of every prefix length
// 0..n of the best-first leaves, each summed on its own, the lengths that
// are not empty and hold at least the budget's triangles; the answer is the
// shortest of them, or all n leaves when no length qualifies (so never none
// when there is a leaf).
#include "strategies/poon_wang_opacity_maps/selection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <random>

namespace occu {
namespace {

TEST(OccluderTriangleBudget, TakesTheShortestPrefixReachingTheBudget)
{
    std::mt19937 rng(17);
    for (int round = 0; round < 500; ++round) {
        std::uniform_int_distribution<std::uint32_t> count(0, 300), length(0, 12);
        std::vector<std::uint32_t> triangles(40);
        for (std::uint32_t &t : triangles)
            t = round % 5 == 0 ? 0 : count(rng);   // now and then leaves of nothing but see-through
        std::vector<std::uint32_t> best_first;
        for (std::uint32_t i = length(rng); i-- > 0;)
            best_first.push_back(std::uniform_int_distribution<std::uint32_t>(0, 39)(rng));
        std::size_t budget = std::uniform_int_distribution<std::size_t>(1, 2000)(rng);
        if (round % 2 == 1 && !best_first.empty()) {
            // A budget some prefix reaches exactly: the boundary between
            // taking a leaf and stopping before it.
            const std::size_t j = std::uniform_int_distribution<std::size_t>(1, best_first.size())(rng);
            budget = 0;
            for (std::size_t i = 0; i < j; ++i)
                budget += triangles[best_first[i]];
            budget = std::max<std::size_t>(budget, 1);
        }

        // Every prefix length, its triangles summed afresh; the qualifying
        // lengths gathered, and the least taken.
        std::vector<std::size_t> qualifying;
        for (std::size_t k = 0; k <= best_first.size(); ++k) {
            const std::size_t held = std::accumulate(
                best_first.begin(), best_first.begin() + std::ptrdiff_t(k), std::size_t{0},
                [&](std::size_t total, std::uint32_t leaf) { return total + triangles.at(leaf); });
            if (k > 0 && held >= budget)
                qualifying.push_back(k);
        }
        const std::size_t expected =
            qualifying.empty() ? best_first.size() : *std::min_element(qualifying.begin(), qualifying.end());
        const auto got = first_leaves_within_triangles(best_first, triangles, budget);
        ASSERT_EQ(got.size(), expected) << "round " << round;
        for (std::size_t i = 0; i < got.size(); ++i)
            ASSERT_EQ(got[i], best_first[i]);
    }
}

TEST(OccluderTriangleBudget, HalvedLeavesTakeTwiceAsManyForTheSameTriangles)
{
    const std::vector<std::uint32_t> big(64, 256), small(128, 128);
    std::vector<std::uint32_t> order_big(64), order_small(128);
    std::iota(order_big.begin(), order_big.end(), 0u);
    std::iota(order_small.begin(), order_small.end(), 0u);
    EXPECT_EQ(first_leaves_within_triangles(order_big, big, 16384).size(), 64u);
    EXPECT_EQ(first_leaves_within_triangles(order_small, small, 16384).size(), 128u);
    EXPECT_TRUE(first_leaves_within_triangles({}, big, 100).empty());
    EXPECT_EQ(first_leaves_within_triangles({3}, big, 1).size(), 1u);
}

}  // namespace
}  // namespace occu
