// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/sparse_depth_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace occu;

namespace {
// Smooth rows (occluder planes at an angle, with steps): long runs.
std::vector<float> smooth(int w, int h, std::mt19937 &rng)
{
    std::uniform_real_distribution<float> u(0, 1);
    std::vector<float> d(std::size_t(w) * std::size_t(h));
    for (int y = 0; y < h; ++y) {
        float z = u(rng), slope = (u(rng) - 0.5f) * 0.05f;
        for (int x = 0; x < w; ++x) {
            if (u(rng) < 0.05f) {   // another occluder starts
                z = u(rng);
                slope = (u(rng) - 0.5f) * 0.05f;
            }
            z = std::clamp(z + slope, 0.0f, 1.0f);
            d[std::size_t(y) * std::size_t(w) + std::size_t(x)] = z;
        }
    }
    return d;
}

// Depth alternating near/far at every pixel: every run is one pixel.
std::vector<float> alternating(int w, int h)
{
    std::vector<float> d(std::size_t(w) * std::size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            d[std::size_t(y) * std::size_t(w) + std::size_t(x)] = (x + y) % 2 ? 0.7f : 0.3f;
    return d;
}

void expect_equals_pixelwise(const SparseDepthMap &m, int w, int h, std::mt19937 &rng, const std::vector<float> &d)
{
    std::uniform_int_distribution<int> px(0, w - 1), py(0, h - 1);
    std::uniform_real_distribution<float> z(0, 1);
    int behind = 0;
    for (int i = 0; i < 4000; ++i) {
        int x0 = px(rng), x1 = px(rng), y0 = py(rng), y1 = py(rng);
        if (x0 > x1) std::swap(x0, x1);
        if (y0 > y1) std::swap(y0, y1);
        // Depths equal to a map value (strictness), uniform, and far away.
        const float zn = i % 3 == 0   ? d[std::size_t(py(rng)) * std::size_t(w) + std::size_t(px(rng))]
                         : i % 3 == 1 ? z(rng)
                                      : 0.9f + 0.1f * z(rng);
        const bool expected = m.behind_pixelwise(zn, x0, x1, y0, y1);
        ASSERT_EQ(m.behind(zn, x0, x1, y0, y1), expected) << x0 << ".." << x1 << " x " << y0 << ".." << y1 << " z " << zn;
        behind += expected;
    }
    EXPECT_GT(behind, 100);   // both outcomes exercised
}
}  // namespace

TEST(SparseDepthMap, EqualsPixelwiseComparisonOnRandomDepthMaps)
{
    std::mt19937 rng(11);
    for (int trial = 0; trial < 5; ++trial) {
        const int w = 64 + trial * 13, h = 40;
        const auto d = smooth(w, h, rng);
        const SparseDepthMap m(w, h, d);
        EXPECT_TRUE(m.worthwhile()) << m.mean_run_length();
        expect_equals_pixelwise(m, w, h, rng, d);
    }
}

TEST(SparseDepthMap, AlternatingRowsAreNotWorthwhileButStillExact)
{
    std::mt19937 rng(12);
    const auto d = alternating(50, 30);
    const SparseDepthMap m(50, 30, d);
    EXPECT_FALSE(m.worthwhile());
    EXPECT_LE(m.mean_run_length(), 2.0);
    expect_equals_pixelwise(m, 50, 30, rng, d);
}

TEST(SparseDepthMap, SkipsReachTheRunsPeak)
{
    // One row: rising 0.1 0.2 0.3, falling to 0.1, rising 0.2: runs of 3 and 2.
    const SparseDepthMap m(5, 1, {0.1f, 0.2f, 0.3f, 0.1f, 0.2f});
    EXPECT_EQ(m.skip(0, 0), 3);
    EXPECT_EQ(m.skip(1, 0), 2);
    EXPECT_EQ(m.skip(2, 0), 1);
    EXPECT_EQ(m.skip(3, 0), 2);
    EXPECT_TRUE(m.behind(0.31f, 0, 4, 0, 0));
    EXPECT_FALSE(m.behind(0.3f, 0, 4, 0, 0));   // equal is not behind
    EXPECT_TRUE(m.behind(0.25f, 3, 4, 0, 0));
}
