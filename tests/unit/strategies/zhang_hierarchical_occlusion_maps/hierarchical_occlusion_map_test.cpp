// SPDX-License-Identifier: MIT
#include "strategies/zhang_hierarchical_occlusion_maps/hierarchical_occlusion_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

using namespace occu;

namespace {
const std::vector<std::pair<int, int>> sizes{{1, 1}, {1, 7}, {7, 1}, {13, 5}, {256, 256}, {300, 200}};

std::size_t at(int w, int x, int y) { return std::size_t(y) * std::size_t(w) + std::size_t(x); }

// Occluders drawn into an occlusion map and a depth image together: each
// a rectangle, flat or sloped, nearest wins; opacity 1 and depth < 1 where
// one is. Around them the background (opacity 0, depth 1) with some pixels
// partly covered (antialiased edges: opacity in (0, 1), depth 1), and a few
// covered pixels not quite opaque (1 - 2^-24 and the like: depth < 1).
struct Occluders {
    std::vector<float> opacity, depth;
};
Occluders occluders(int w, int h, std::mt19937 &rng)
{
    std::uniform_real_distribution<float> u(0, 1);
    Occluders o{std::vector<float>(std::size_t(w) * std::size_t(h), 0.0f),
                std::vector<float>(std::size_t(w) * std::size_t(h), 1.0f)};
    const int count = 1 + int(u(rng) * 8);
    for (int i = 0; i < count; ++i) {
        const int x0 = int(u(rng) * float(w)), y0 = int(u(rng) * float(h));
        const int x1 = std::min(w, x0 + 1 + int(u(rng) * float(w))), y1 = std::min(h, y0 + 1 + int(u(rng) * float(h)));
        const float z = 0.1f + 0.7f * u(rng), sx = (u(rng) - 0.5f) * 0.004f, sy = (u(rng) - 0.5f) * 0.004f;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                float &d = o.depth[at(w, x, y)];
                d = std::min(d, std::clamp(z + sx * float(x - x0) + sy * float(y - y0), 0.0f, 0.99f));
                o.opacity[at(w, x, y)] = 1.0f;
            }
    }
    const float almost[] = {std::nextafter(1.0f, 0.0f), 1.0f - 1.0f / 256.0f, 0.5f};
    for (std::size_t i = 0; i < o.opacity.size(); ++i) {
        if (o.opacity[i] == 0.0f && u(rng) < 0.05f)
            o.opacity[i] = u(rng);
        else if (o.opacity[i] == 1.0f && u(rng) < 0.003f)
            o.opacity[i] = almost[int(u(rng) * 3) % 3];
    }
    return o;
}

// Opacities k / 16, mostly 1 (occluders) and 0, for thresholds without
// rounding.
std::vector<float> dyadic_opacity(int w, int h, std::mt19937 &rng)
{
    std::uniform_real_distribution<float> u(0, 1);
    std::vector<float> o(std::size_t(w) * std::size_t(h), u(rng) < 0.5f ? 0.0f : 1.0f);
    const int count = 1 + int(u(rng) * 6);
    for (int i = 0; i < count; ++i) {
        const int x0 = int(u(rng) * float(w)), y0 = int(u(rng) * float(h));
        const int x1 = std::min(w, x0 + 1 + int(u(rng) * float(w))), y1 = std::min(h, y0 + 1 + int(u(rng) * float(h)));
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
                o[at(w, x, y)] = 1.0f;
    }
    const float mixed = u(rng) * 0.3f;   // per image: how many pixels partly covered
    for (float &p : o)
        if (u(rng) < mixed)
            p = float(int(u(rng) * 17) % 17) / 16.0f;
    return o;
}

PixelRect random_rect(int w, int h, std::mt19937 &rng)
{
    std::uniform_real_distribution<double> u(0, 1);
    const int rw = std::max(1, int(std::exp(u(rng) * std::log(w + 4.0))));
    const int rh = std::max(1, int(std::exp(u(rng) * std::log(h + 4.0))));
    const int x0 = -rw / 2 - 1 + int(u(rng) * double(w + rw / 2 + 2));
    const int y0 = -rh / 2 - 1 + int(u(rng) * double(h + rh / 2 + 2));
    return {x0, y0, x0 + rw, y0 + rh};
}

// The references, pixel by pixel over the clamped rectangle (empty: false).
bool every_pixel_at_least(const std::vector<float> &opacity, int w, int h, const PixelRect &rect, float threshold)
{
    const PixelRect r = rect.clamped({0, 0, w, h});
    if (r.empty())
        return false;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
            if (!(opacity[at(w, x, y)] >= threshold))
                return false;
    return true;
}

bool occluded_pixelwise(const Occluders &o, int w, int h, const PixelRect &rect, float z)
{
    const PixelRect r = rect.clamped({0, 0, w, h});
    if (r.empty())
        return false;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
            if (!(o.opacity[at(w, x, y)] == 1.0f && o.depth[at(w, x, y)] < z))
                return false;
    return true;
}

// The region of each pixel, from the rule in the header.
int region_of(int p, int regions, int size) { return int(std::int64_t(p) * regions / size); }

// What the depth estimation buffer holds for the regions `rect` touches,
// brute force from the rule in the header: the farthest of each touched
// region's farthest covered depth (< 1), a region without covered pixels
// counting 1; -1 when the rectangle touches nothing.
float touched_regions_farthest(const std::vector<float> &depth, int w, int h, int rx, int ry, const PixelRect &rect)
{
    const PixelRect r = rect.clamped({0, 0, w, h});
    std::vector<char> touched(std::size_t(rx) * std::size_t(ry), 0);
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
            touched[std::size_t(region_of(y, ry, h)) * std::size_t(rx) + std::size_t(region_of(x, rx, w))] = 1;
    std::vector<float> region_far(touched.size(), -1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t g = std::size_t(region_of(y, ry, h)) * std::size_t(rx) + std::size_t(region_of(x, rx, w));
            if (depth[at(w, x, y)] < 1.0f)
                region_far[g] = std::max(region_far[g], depth[at(w, x, y)]);
        }
    float far = -1.0f;
    for (std::size_t g = 0; g < touched.size(); ++g)
        if (touched[g])
            far = std::max(far, region_far[g] < 0 ? 1.0f : region_far[g]);
    return far;
}
}  // namespace

// --- the hierarchical occlusion map ---------------------------------------

TEST(HierarchicalOcclusionMap, LevelsAreTheMeanOpacityOfTheLevel0PixelsTheyCover)
{
    std::mt19937 rng(31);
    HierarchicalOcclusionMap hom;
    for (const auto &[w, h] : sizes) {
        const auto o = occluders(w, h, rng).opacity;
        hom.build(w, h, o.data());
        int k = 0;
        for (int lw = w, lh = h;; lw = (lw + 1) / 2, lh = (lh + 1) / 2, ++k) {
            ASSERT_LT(k, hom.levels());
            ASSERT_EQ(hom.level(k).width, lw);
            ASSERT_EQ(hom.level(k).height, lh);
            if (lw == 1 && lh == 1)
                break;
        }
        ASSERT_EQ(hom.levels(), k + 1);
        for (k = 0; k < hom.levels(); ++k) {
            const auto level = hom.level(k);
            const int side = 1 << k;
            for (int y = 0; y < level.height; ++y)
                for (int x = 0; x < level.width; ++x) {
                    const PixelRect f = PixelRect{x * side, y * side, (x + 1) * side, (y + 1) * side}.clamped({0, 0, w, h});
                    double transparency = 0;
                    bool opaque = true;
                    for (int py = f.y0; py < f.y1; ++py)
                        for (int px = f.x0; px < f.x1; ++px) {
                            transparency += 1.0 - double(o[at(w, px, py)]);
                            opaque = opaque && o[at(w, px, py)] == 1.0f;
                        }
                    transparency /= double(f.area());
                    ASSERT_NEAR(level.transparency_at(x, y), transparency, 1e-6 * transparency + 1e-12)
                        << w << "x" << h << " level " << k << " texel " << x << "," << y;
                    ASSERT_NEAR(level.opacity_at(x, y), 1.0 - transparency, 1e-6);
                    // Exactly zero transparency only when every pixel is opaque.
                    ASSERT_EQ(level.transparency_at(x, y) == 0.0f, opaque)
                        << w << "x" << h << " level " << k << " texel " << x << "," << y;
                }
        }
    }
}

TEST(HierarchicalOcclusionMap, BorderTexelsAverageOnlyThePixelsThatExist)
{
    // 3 x 1: level 1 is {mean(a, b), c}; level 2 is (a + b + c) / 3, not the
    // plain mean of level 1's two texels.
    const float o[] = {1.0f, 1.0f, 0.25f};
    HierarchicalOcclusionMap hom;
    hom.build(3, 1, o);
    ASSERT_EQ(hom.levels(), 3);
    EXPECT_FLOAT_EQ(hom.level(1).opacity_at(0, 0), 1.0f);
    EXPECT_FLOAT_EQ(hom.level(1).opacity_at(1, 0), 0.25f);
    EXPECT_FLOAT_EQ(hom.level(2).opacity_at(0, 0), 0.75f);
}

TEST(HierarchicalOcclusionMap, ThresholdsFollowZhangsRecursionAndGrowTowardsCoarseLevels)
{
    for (double o0 : {1.0, 0.9375, 0.75, 0.5, 0.0}) {
        EXPECT_DOUBLE_EQ(HierarchicalOcclusionMap::level_threshold(o0, 0), o0);
        for (int k = 0; k < 12; ++k) {
            const double ok = HierarchicalOcclusionMap::level_threshold(o0, k);
            const double next = HierarchicalOcclusionMap::level_threshold(o0, k + 1);
            EXPECT_DOUBLE_EQ(next, (3.0 + ok) / 4.0) << o0 << " level " << k;
            EXPECT_GE(next, ok);
            EXPECT_LE(next, 1.0);
        }
    }
    // The paper's example: a 2x2 hole in an 8x8 block, O_0 = 1 - 4/64; the
    // next level's 16x16 block gives 1 - 4/256.
    EXPECT_DOUBLE_EQ(HierarchicalOcclusionMap::level_threshold(1.0 - 4.0 / 64.0, 1), 1.0 - 4.0 / 256.0);
    // Exact culling: every level needs full opacity.
    for (int k = 0; k < 26; ++k)
        EXPECT_EQ(HierarchicalOcclusionMap::level_threshold(1.0, k), 1.0);
}

TEST(HierarchicalOcclusionMap, ExactOverlapEqualsEveryPixelFullyOpaque)
{
    std::mt19937 rng(32);
    HierarchicalOcclusionMap hom;
    int covered = 0, uncovered = 0;
    for (const auto &[w, h] : sizes) {
        for (int image = 0; image < 6; ++image) {
            const auto o = occluders(w, h, rng).opacity;
            hom.build(w, h, o.data());
            for (int i = 0; i < 700; ++i) {
                const PixelRect rect = random_rect(w, h, rng);
                const bool expected = every_pixel_at_least(o, w, h, rect, 1.0f);
                ASSERT_EQ(hom.overlaps(rect), expected) << w << "x" << h << " rect [" << rect.x0 << "," << rect.x1
                                                        << ")x[" << rect.y0 << "," << rect.y1 << ")";
                ASSERT_EQ(hom.overlaps(rect, 1.0f), expected);
                (expected ? covered : uncovered)++;
            }
        }
    }
    EXPECT_GT(covered, 3000);
    EXPECT_GT(uncovered, 3000);
}

TEST(HierarchicalOcclusionMap, AlmostOpaquePixelsAreNotOpaque)
{
    // One pixel at 1 - 2^-24 in 256x256: a float mean of opacities would
    // round every texel above it to 1.
    std::vector<float> o(256 * 256, 1.0f);
    o[at(256, 200, 77)] = std::nextafter(1.0f, 0.0f);
    HierarchicalOcclusionMap hom;
    hom.build(256, 256, o.data());
    EXPECT_GT(hom.level(hom.levels() - 1).transparency_at(0, 0), 0.0f);
    EXPECT_FALSE(hom.overlaps({0, 0, 256, 256}));
    EXPECT_TRUE(hom.overlaps({0, 0, 200, 256}));
    EXPECT_TRUE(hom.overlaps({0, 0, 256, 256}, 0.99f));
}

TEST(HierarchicalOcclusionMap, ApproximateOverlapEqualsEveryPixelAtLeastTheThreshold)
{
    // What the thresholds O_k = 1 - (1 - O_0) / 4^k guarantee (header): the
    // hierarchical test passes exactly when every level-0 pixel of the
    // rectangle has opacity >= O_0. Dyadic opacities: no rounding at all.
    std::mt19937 rng(33);
    HierarchicalOcclusionMap hom;
    int passed = 0, failed = 0, passed_only_approximately = 0;
    for (const auto &[w, h] : sizes) {
        for (int image = 0; image < 6; ++image) {
            const auto o = dyadic_opacity(w, h, rng);
            hom.build(w, h, o.data());
            for (int i = 0; i < 500; ++i) {
                const PixelRect rect = random_rect(w, h, rng);
                for (float o0 : {1.0f, 15.0f / 16.0f, 0.75f, 0.5f, 0.25f, 1.0f / 16.0f, 0.0f}) {
                    const bool expected = every_pixel_at_least(o, w, h, rect, o0);
                    ASSERT_EQ(hom.overlaps(rect, o0), expected)
                        << w << "x" << h << " O_0 " << o0 << " rect [" << rect.x0 << "," << rect.x1 << ")x["
                        << rect.y0 << "," << rect.y1 << ")";
                    (expected ? passed : failed)++;
                    passed_only_approximately += expected && o0 < 1.0f && !hom.overlaps(rect, 1.0f);
                }
            }
        }
    }
    EXPECT_GT(passed, 5000);
    EXPECT_GT(failed, 5000);
    EXPECT_GT(passed_only_approximately, 1000);

    // Continuous opacities (ties have probability zero).
    for (const auto &[w, h] : sizes) {
        for (int image = 0; image < 3; ++image) {
            const auto o = occluders(w, h, rng).opacity;
            hom.build(w, h, o.data());
            for (int i = 0; i < 500; ++i) {
                const PixelRect rect = random_rect(w, h, rng);
                for (float o0 : {0.99f, 0.9f, 0.6f, 0.3f})
                    ASSERT_EQ(hom.overlaps(rect, o0), every_pixel_at_least(o, w, h, rect, o0))
                        << w << "x" << h << " O_0 " << o0 << " rect [" << rect.x0 << "," << rect.x1 << ")x["
                        << rect.y0 << "," << rect.y1 << ")";
            }
        }
    }
}

TEST(HierarchicalOcclusionMap, NegligibleHolesSettleAtCoarseLevels)
{
    // 256x256 fully covered but for one pixel at opacity 0.8 in every 16x16
    // block: with O_0 = 0.75 a 16x16 texel holds transparency 0.2 / 256 <=
    // (1 - 0.75) / 256 and settles; exact culling stops at the first hole.
    const int w = 256, h = 256;
    std::vector<float> o(std::size_t(w) * std::size_t(h), 1.0f);
    for (int y = 5; y < h; y += 16)
        for (int x = 11; x < w; x += 16)
            o[at(w, x, y)] = 0.8f;
    HierarchicalOcclusionMap hom;
    hom.build(w, h, o.data());
    const PixelRect whole{0, 0, w, h};
    std::uint64_t visited = 0;
    EXPECT_TRUE(hom.overlaps(whole, 0.75f, &visited));
    EXPECT_EQ(visited, 4u + 16u + 64u + 256u);   // levels 7, 6, 5, 4: all settled there
    EXPECT_FALSE(hom.overlaps(whole, 1.0f));
    EXPECT_FALSE(hom.overlaps(whole, 0.85f));
    // Two holes in a 16x16 block (0.4 > 0.25): that block descends to its
    // four 8x8 quarters, which settle (the holes are in different quarters).
    o[at(w, 3, 13)] = 0.8f;
    hom.build(w, h, o.data());
    visited = 0;
    EXPECT_TRUE(hom.overlaps(whole, 0.75f, &visited));
    EXPECT_EQ(visited, 4u + 16u + 64u + 256u + 4u);
    // Both in one quarter: that quarter descends to its 4x4 quarters too.
    o[at(w, 3, 13)] = 1.0f;
    o[at(w, 12, 5)] = 0.8f;
    hom.build(w, h, o.data());
    visited = 0;
    EXPECT_TRUE(hom.overlaps(whole, 0.75f, &visited));
    EXPECT_EQ(visited, 4u + 16u + 64u + 256u + 4u + 4u);
    EXPECT_FALSE(hom.overlaps(whole, 0.81f));
}

TEST(HierarchicalOcclusionMap, FewTexelsVisitedOverACoveredRegion)
{
    const int w = 256, h = 256;
    std::vector<float> o(std::size_t(w) * std::size_t(h), 0.0f);
    for (int y = 8; y < 248; ++y)
        for (int x = 8; x < 248; ++x)
            o[at(w, x, y)] = 1.0f;
    HierarchicalOcclusionMap hom;
    hom.build(w, h, o.data());
    const PixelRect rect{40, 30, 220, 200};
    std::uint64_t visited = 0;
    EXPECT_TRUE(hom.overlaps(rect, 1.0f, &visited));
    EXPECT_GT(visited, 0u);
    EXPECT_LT(visited * 50, std::uint64_t(rect.area())) << visited << " texels for " << rect.area() << " pixels";
    std::uint64_t again = 0;
    hom.overlaps(rect, 1.0f, &again);
    hom.overlaps(rect, 1.0f, &again);
    EXPECT_EQ(again, 2 * visited);   // the counter adds up
}

TEST(HierarchicalOcclusionMap, EmptyOffImageUnbuiltAndOddThresholds)
{
    HierarchicalOcclusionMap hom;
    EXPECT_FALSE(hom.overlaps({0, 0, 4, 4}));   // before any build
    const std::vector<float> full(13 * 5, 1.0f);
    hom.build(13, 5, full.data());
    EXPECT_TRUE(hom.overlaps({-4, -4, 40, 40}));
    EXPECT_FALSE(hom.overlaps({3, 2, 3, 4}));      // empty
    EXPECT_FALSE(hom.overlaps({13, 0, 20, 5}));    // right of the image
    EXPECT_FALSE(hom.overlaps({0, 0, 13, 5}, std::nanf("")));
    EXPECT_TRUE(hom.overlaps({0, 0, 13, 5}, 2.0f));   // above 1 acts as 1
    const std::vector<float> half(13 * 5, 0.5f);
    hom.build(13, 5, half.data());
    EXPECT_FALSE(hom.overlaps({0, 0, 13, 5}, 2.0f));
    EXPECT_TRUE(hom.overlaps({0, 0, 13, 5}, 0.5f));
    EXPECT_TRUE(hom.overlaps({0, 0, 13, 5}, -1.0f));
    // Out-of-range and NaN opacities: clamped, NaN uncovered.
    std::vector<float> odd(13 * 5, 1.5f);
    hom.build(13, 5, odd.data());
    EXPECT_TRUE(hom.overlaps({0, 0, 13, 5}));
    odd[at(13, 12, 4)] = std::nanf("");
    hom.build(13, 5, odd.data());
    EXPECT_FALSE(hom.overlaps({0, 0, 13, 5}, 0.0001f));
    EXPECT_EQ(hom.level(0).transparency_at(12, 4), 1.0f);
    EXPECT_THROW(hom.build(4, -1, odd.data()), std::invalid_argument);
}

TEST(HierarchicalOcclusionMap, RebuildReusesStorageAndForgetsThePreviousImage)
{
    std::vector<float> none(300 * 200, 0.0f), all(300 * 200, 1.0f);
    HierarchicalOcclusionMap hom;
    hom.build(300, 200, all.data());
    const float *storage = hom.level(0).transparency;
    EXPECT_TRUE(hom.overlaps({0, 0, 300, 200}));
    hom.build(13, 5, none.data());
    EXPECT_EQ(hom.level(0).transparency, storage);
    EXPECT_FALSE(hom.overlaps({0, 0, 13, 5}));
    hom.build(300, 200, none.data());
    EXPECT_EQ(hom.level(0).transparency, storage);
    EXPECT_FALSE(hom.overlaps({0, 0, 300, 200}));
}

// --- the depth estimation buffer ---------------------------------------------

TEST(DepthEstimationBuffer, RegionsPartitionTheImageAndHoldTheFarthestCoveredDepth)
{
    std::mt19937 rng(41);
    for (const auto &[w, h] : sizes) {
        for (const auto &[rx, ry] : std::vector<std::pair<int, int>>{{64, 64}, {8, 8}, {3, 5}, {1, 1}}) {
            const auto o = occluders(w, h, rng);
            DepthEstimationBuffer deb(rx, ry);
            deb.build(w, h, o.depth.data());
            ASSERT_EQ(deb.regions_x(), rx);
            ASSERT_EQ(deb.regions_y(), ry);
            std::vector<int> owner(std::size_t(w) * std::size_t(h), 0);
            for (int gy = 0; gy < ry; ++gy)
                for (int gx = 0; gx < rx; ++gx) {
                    const PixelRect pixels = deb.region_pixels(gx, gy);
                    float far = -1.0f;
                    for (int y = std::max(pixels.y0, 0); y < pixels.y1; ++y)
                        for (int x = std::max(pixels.x0, 0); x < pixels.x1; ++x) {
                            ++owner[at(w, x, y)];
                            ASSERT_EQ(region_of(x, rx, w), gx);
                            ASSERT_EQ(region_of(y, ry, h), gy);
                            if (o.depth[at(w, x, y)] < 1.0f)
                                far = std::max(far, o.depth[at(w, x, y)]);
                        }
                    const float expected = pixels.empty() ? -std::numeric_limits<float>::infinity()
                                           : far < 0            ? 1.0f
                                                                : far;
                    ASSERT_EQ(deb.farthest(gx, gy), expected)
                        << w << "x" << h << " in " << rx << "x" << ry << " region " << gx << "," << gy;
                    if (!pixels.empty()) {
                        ASSERT_EQ(deb.regions_touched(pixels), (PixelRect{gx, gy, gx + 1, gy + 1}));
                    }
                }
            for (int n : owner)
                ASSERT_EQ(n, 1) << w << "x" << h << " in " << rx << "x" << ry;   // each pixel in one region
        }
    }
}

TEST(DepthEstimationBuffer, BehindEqualsComparisonWithEveryTouchedRegion)
{
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(0, 1);
    int behind = 0, not_behind = 0;
    for (const auto &[w, h] : sizes) {
        for (const auto &[rx, ry] : std::vector<std::pair<int, int>>{{64, 64}, {8, 8}, {3, 5}}) {
            const auto o = occluders(w, h, rng);
            DepthEstimationBuffer deb(rx, ry);
            deb.build(w, h, o.depth.data());
            for (int i = 0; i < 400; ++i) {
                const PixelRect rect = random_rect(w, h, rng);
                const float far = touched_regions_farthest(o.depth, w, h, rx, ry, rect);
                // That depth itself (not behind), the next float (behind),
                // uniform.
                for (float z : {far, std::nextafter(far, 2.0f), u(rng)}) {
                    const bool expected = far >= 0.0f && z > far;
                    ASSERT_EQ(deb.behind(rect, z), expected)
                        << w << "x" << h << " regions " << rx << "x" << ry << " rect [" << rect.x0 << "," << rect.x1
                        << ")x[" << rect.y0 << "," << rect.y1 << ") z " << z;
                    (expected ? behind : not_behind)++;
                }
            }
        }
    }
    EXPECT_GT(behind, 1000);
    EXPECT_GT(not_behind, 1000);
}

TEST(DepthEstimationBuffer, WithTheExactOverlapTestItIsConservative)
{
    // overlaps(rect, 1) && behind(rect, z) must imply that every pixel of the
    // rectangle is covered by an occluder nearer than z; the converse fails
    // only by the regions' coarseness.
    std::mt19937 rng(43);
    std::uniform_real_distribution<float> u(0, 1);
    int occluded = 0, culled = 0, missed_by_coarseness = 0;
    HierarchicalOcclusionMap hom;
    for (const auto &[w, h] : sizes) {
        for (const auto &[rx, ry] : std::vector<std::pair<int, int>>{{64, 64}, {16, 16}, {5, 3}}) {
            for (int image = 0; image < 3; ++image) {
                const auto o = occluders(w, h, rng);
                hom.build(w, h, o.opacity.data());
                DepthEstimationBuffer deb(rx, ry);
                deb.build(w, h, o.depth.data());
                for (int i = 0; i < 400; ++i) {
                    const PixelRect rect = random_rect(w, h, rng);
                    const PixelRect inside = rect.clamped({0, 0, w, h});
                    float rect_far = 0.0f;   // the rectangle's own farthest depth
                    for (int y = inside.y0; y < inside.y1; ++y)
                        for (int x = inside.x0; x < inside.x1; ++x)
                            rect_far = std::max(rect_far, o.depth[at(w, x, y)]);
                    const float regions_far = touched_regions_farthest(o.depth, w, h, rx, ry, rect);
                    for (float z : {std::nextafter(rect_far, 2.0f), std::nextafter(regions_far, 2.0f), u(rng)}) {
                        const bool brute = occluded_pixelwise(o, w, h, rect, z);
                        const bool overlap = hom.overlaps(rect, 1.0f);
                        const bool both = overlap && deb.behind(rect, z);
                        ASSERT_TRUE(!both || brute) << w << "x" << h << " regions " << rx << "x" << ry << " rect ["
                                                    << rect.x0 << "," << rect.x1 << ")x[" << rect.y0 << ","
                                                    << rect.y1 << ") z " << z;
                        occluded += brute;
                        culled += both;
                        if (brute && !both) {
                            // The overlap test is exact, so the depth test
                            // failed: some covered pixel of a touched region,
                            // outside the rectangle, is not nearer than z.
                            ASSERT_TRUE(overlap);
                            ASSERT_GE(regions_far, z);
                            ASSERT_LT(rect_far, z);
                            ++missed_by_coarseness;
                        }
                    }
                }
            }
        }
    }
    EXPECT_GT(culled, 1000);
    EXPECT_GT(missed_by_coarseness, 100);
    EXPECT_EQ(culled + missed_by_coarseness, occluded);
}

TEST(DepthEstimationBuffer, OneRegionPerPixelMakesTheCombinationExact)
{
    std::mt19937 rng(44);
    std::uniform_real_distribution<float> u(0, 1);
    HierarchicalOcclusionMap hom;
    int occluded = 0;
    for (const auto &[w, h] : sizes) {
        const auto o = occluders(w, h, rng);
        hom.build(w, h, o.opacity.data());
        DepthEstimationBuffer deb(w, h);
        deb.build(w, h, o.depth.data());
        for (int i = 0; i < 1000; ++i) {
            const PixelRect rect = random_rect(w, h, rng);
            const float z = i % 2 ? u(rng) : 0.9f + 0.1f * u(rng);
            const bool brute = occluded_pixelwise(o, w, h, rect, z);
            ASSERT_EQ(hom.overlaps(rect) && deb.behind(rect, z), brute) << w << "x" << h << " z " << z;
            occluded += brute;
        }
    }
    EXPECT_GT(occluded, 500);
}

TEST(DepthEstimationBuffer, AloneItSaysNothingAboutUncoveredPixels)
{
    // 8x8, one region: an occluder at 0.2 over the left half, nothing on the
    // right. behind() passes a rectangle over the empty right half (the
    // region's farthest covered depth is 0.2); the overlap test does not.
    std::vector<float> depth(64, 1.0f), opacity(64, 0.0f);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 4; ++x) {
            depth[at(8, x, y)] = 0.2f;
            opacity[at(8, x, y)] = 1.0f;
        }
    DepthEstimationBuffer deb(1, 1);
    deb.build(8, 8, depth.data());
    HierarchicalOcclusionMap hom;
    hom.build(8, 8, opacity.data());
    const PixelRect right{4, 0, 8, 8};
    EXPECT_EQ(deb.farthest(0, 0), 0.2f);
    EXPECT_TRUE(deb.behind(right, 0.5f));
    EXPECT_FALSE(hom.overlaps(right));
    EXPECT_TRUE(hom.overlaps({0, 0, 4, 8}) && deb.behind({0, 0, 4, 8}, 0.5f));
}

TEST(DepthEstimationBuffer, EmptyRegionsHold1AndBadInputIsConservative)
{
    std::vector<float> depth(8 * 8, 1.0f);
    depth[at(8, 1, 1)] = 0.3f;
    depth[at(8, 6, 6)] = std::nanf("");
    DepthEstimationBuffer deb(2, 2);
    deb.build(8, 8, depth.data());
    EXPECT_EQ(deb.farthest(0, 0), 0.3f);
    EXPECT_EQ(deb.farthest(1, 0), 1.0f);   // no occluder
    EXPECT_EQ(deb.farthest(1, 1), 1.0f);   // NaN: covered at 1
    EXPECT_TRUE(deb.behind({0, 0, 4, 4}, 0.31f));
    EXPECT_FALSE(deb.behind({0, 0, 4, 4}, 0.3f));   // equal is not behind
    EXPECT_FALSE(deb.behind({0, 0, 5, 4}, 0.99f));   // touches an empty region
    EXPECT_FALSE(deb.behind({0, 0, 4, 4}, std::nanf("")));
    EXPECT_FALSE(deb.behind({2, 2, 2, 3}, 0.9f));     // empty rectangle
    EXPECT_FALSE(deb.behind({8, 0, 9, 8}, 0.9f));     // off the image
    DepthEstimationBuffer unbuilt;
    EXPECT_EQ(unbuilt.regions_x(), 64);
    EXPECT_FALSE(unbuilt.behind({0, 0, 4, 4}, 0.9f));
    EXPECT_THROW(DepthEstimationBuffer(0, 4), std::invalid_argument);
    EXPECT_THROW(deb.build(-1, 4, depth.data()), std::invalid_argument);
    // Rebuilding forgets the previous image and keeps the storage.
    const std::vector<float> near(8 * 8, 0.1f);
    deb.build(8, 8, near.data());
    EXPECT_TRUE(deb.behind({0, 0, 8, 8}, 0.2f));
}
