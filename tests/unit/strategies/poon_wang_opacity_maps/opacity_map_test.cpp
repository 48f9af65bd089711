// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/opacity_map.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

using namespace occu;

namespace {
std::uint32_t brute_force(const std::vector<std::uint8_t> &bits, int w, int x1, int x2, int y1, int y2)
{
    std::uint32_t n = 0;
    for (int y = y1 + 1; y <= y2; ++y)
        for (int x = x1 + 1; x <= x2; ++x)
            n += bits[std::size_t(y - 1) * std::size_t(w) + std::size_t(x - 1)] != 0;
    return n;
}
}  // namespace

TEST(OpacityMap, OpacityFunctionEqualsBruteForceOnRandomBitmapsBordersIncluded)
{
    std::mt19937 rng(3);
    for (const auto &[w, h] : std::vector<std::pair<int, int>>{{1, 1}, {1, 9}, {9, 1}, {17, 13}, {32, 32}}) {
        for (double density : {0.1, 0.5, 0.95}) {
            std::bernoulli_distribution on(density);
            std::vector<std::uint8_t> bits(std::size_t(w) * std::size_t(h));
            for (auto &b : bits)
                b = on(rng);
            const OpacityMap map(w, h, bits);
            // Every rectangle, the zero row and column and the far borders included.
            for (int x1 = 0; x1 <= w; ++x1)
                for (int x2 = x1; x2 <= w; ++x2)
                    for (int y1 = 0; y1 <= h; y1 += (h > 16 ? 3 : 1))
                        for (int y2 = y1; y2 <= h; ++y2)
                            ASSERT_EQ(map.covered(x1, x2, y1, y2), brute_force(bits, w, x1, x2, y1, y2))
                                << w << "x" << h << " (" << x1 << "," << x2 << "," << y1 << "," << y2 << ")";
        }
    }
}

TEST(OpacityMap, OverlapTestsExactApproximateAndAdaptive)
{
    // A 4x3 bitmap, all covered but one pixel at (2, 2) (1-based).
    std::vector<std::uint8_t> bits(12, 1);
    bits[1 * 4 + 1] = 0;
    const OpacityMap map(4, 3, bits);
    EXPECT_FALSE(map.overlaps_fully(0, 4, 0, 3));      // the hole
    EXPECT_TRUE(map.overlaps_fully(0, 4, 0, 3, 1));    // tolerating one hole pixel
    EXPECT_TRUE(map.overlaps_fully(2, 4, 0, 3));       // the hole is outside
    EXPECT_DOUBLE_EQ(map.coverage_ratio(0, 4, 0, 3), 11.0 / 12.0);
    EXPECT_DOUBLE_EQ(map.coverage_ratio(1, 1, 0, 3), 1.0);   // empty rectangle
    EXPECT_THROW(OpacityMap(4, 3, std::vector<std::uint8_t>(11)), std::invalid_argument);
}
