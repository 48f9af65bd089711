// SPDX-License-Identifier: MIT
#include "strategies/greene_hierarchical_z_buffer/z_pyramid.h"

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

float at(const std::vector<float> &d, int w, int x, int y) { return d[std::size_t(y) * std::size_t(w) + std::size_t(x)]; }

// A depth image like a frame's: cleared to 1, occluder rectangles (flat or
// sloped) drawn nearest-wins, and a little per-pixel noise.
std::vector<float> scene(int w, int h, std::mt19937 &rng)
{
    std::uniform_real_distribution<float> u(0, 1);
    std::vector<float> d(std::size_t(w) * std::size_t(h), 1.0f);
    const int occluders = 1 + int(u(rng) * 8);
    for (int i = 0; i < occluders; ++i) {
        const int x0 = int(u(rng) * float(w)), y0 = int(u(rng) * float(h));
        const int x1 = std::min(w, x0 + 1 + int(u(rng) * float(w))), y1 = std::min(h, y0 + 1 + int(u(rng) * float(h)));
        const float z = 0.1f + 0.7f * u(rng), sx = (u(rng) - 0.5f) * 0.002f, sy = (u(rng) - 0.5f) * 0.002f;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                float &p = d[std::size_t(y) * std::size_t(w) + std::size_t(x)];
                p = std::min(p, std::clamp(z + sx * float(x - x0) + sy * float(y - y0), 0.0f, 0.99f));
            }
    }
    for (float &p : d)
        if (u(rng) < 0.01f)
            p = u(rng);
    return d;
}

// Rectangles of every size from one pixel to past the image, some sticking
// out of it or wholly outside.
PixelRect random_rect(int w, int h, std::mt19937 &rng)
{
    std::uniform_real_distribution<double> u(0, 1);
    const int rw = std::max(1, int(std::exp(u(rng) * std::log(w + 4.0))));
    const int rh = std::max(1, int(std::exp(u(rng) * std::log(h + 4.0))));
    const int x0 = -rw / 2 - 1 + int(u(rng) * double(w + rw / 2 + 2));
    const int y0 = -rh / 2 - 1 + int(u(rng) * double(h + rh / 2 + 2));
    return {x0, y0, x0 + rw, y0 + rh};
}

// The reference: every pixel of the clamped rectangle nearer than z (an
// empty one: false).
bool occluded_pixelwise(const std::vector<float> &d, int w, int h, const PixelRect &rect, float z)
{
    const PixelRect r = rect.clamped({0, 0, w, h});
    if (r.empty())
        return false;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
            if (!(at(d, w, x, y) < z))
                return false;
    return true;
}

float farthest_in(const std::vector<float> &d, int w, const PixelRect &r)
{
    float far = -1.0f;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
            far = std::max(far, at(d, w, x, y));
    return far;
}
}  // namespace

TEST(ZPyramid, LevelsHalveRoundingUpDownTo1x1)
{
    ZPyramid zp;
    EXPECT_EQ(zp.levels(), 0);
    for (const auto &[w, h] : sizes) {
        const std::vector<float> d(std::size_t(w) * std::size_t(h), 0.5f);
        zp.build(w, h, d.data());
        int k = 0;
        for (int lw = w, lh = h;; lw = (lw + 1) / 2, lh = (lh + 1) / 2, ++k) {
            ASSERT_LT(k, zp.levels()) << w << "x" << h;
            EXPECT_EQ(zp.level(k).width, lw) << w << "x" << h << " level " << k;
            EXPECT_EQ(zp.level(k).height, lh) << w << "x" << h << " level " << k;
            if (lw == 1 && lh == 1)
                break;
        }
        EXPECT_EQ(zp.levels(), k + 1) << w << "x" << h;
        EXPECT_EQ(zp.width(), w);
        EXPECT_EQ(zp.height(), h);
    }
    // 256 = 2^8: nine levels; 300x200: 300 150 75 38 19 10 5 3 2 1.
    const std::vector<float> d(300 * 256, 0.5f);
    zp.build(256, 256, d.data());
    EXPECT_EQ(zp.levels(), 9);
    zp.build(300, 200, d.data());
    EXPECT_EQ(zp.levels(), 10);
}

TEST(ZPyramid, EachTexelHoldsTheFarthestDepthOfItsFootprint)
{
    std::mt19937 rng(21);
    ZPyramid zp;
    for (const auto &[w, h] : sizes) {
        const auto d = scene(w, h, rng);
        zp.build(w, h, d.data());
        ASSERT_EQ(zp.level(0).at(w - 1, h - 1), at(d, w, w - 1, h - 1));
        for (int k = 0; k < zp.levels(); ++k) {
            const auto level = zp.level(k);
            const int side = 1 << k;
            for (int y = 0; y < level.height; ++y)
                for (int x = 0; x < level.width; ++x) {
                    const PixelRect footprint =
                        PixelRect{x * side, y * side, (x + 1) * side, (y + 1) * side}.clamped({0, 0, w, h});
                    ASSERT_FALSE(footprint.empty());
                    ASSERT_EQ(level.at(x, y), farthest_in(d, w, footprint))
                        << w << "x" << h << " level " << k << " texel " << x << "," << y;
                }
        }
    }
}

TEST(ZPyramid, OccludedEqualsPixelByPixelComparisonOnRandomImagesAndRects)
{
    std::mt19937 rng(22);
    std::uniform_real_distribution<float> u(0, 1);
    ZPyramid zp;
    int occluded = 0, visible = 0;
    for (const auto &[w, h] : sizes) {
        for (int image = 0; image < 6; ++image) {
            const auto d = scene(w, h, rng);
            zp.build(w, h, d.data());
            for (int i = 0; i < 800; ++i) {
                const PixelRect rect = random_rect(w, h, rng);
                const PixelRect inside = rect.clamped({0, 0, w, h});
                const float far = inside.empty() ? 0.5f : farthest_in(d, w, inside);
                // Depths at the boundary (the farthest itself, not behind it,
                // and the next float, behind it), uniform, and a stored one.
                float z = 0;
                switch (i % 4) {
                case 0: z = far; break;
                case 1: z = std::nextafter(far, 2.0f); break;
                case 2: z = u(rng); break;
                default: z = at(d, w, int(u(rng) * float(w)) % w, int(u(rng) * float(h)) % h); break;
                }
                const bool expected = occluded_pixelwise(d, w, h, rect, z);
                ASSERT_EQ(zp.occluded(rect, z), expected)
                    << w << "x" << h << " rect [" << rect.x0 << "," << rect.x1 << ")x[" << rect.y0 << "," << rect.y1
                    << ") z " << z;
                (expected ? occluded : visible)++;
            }
        }
    }
    EXPECT_GT(occluded, 3000);   // both outcomes well exercised
    EXPECT_GT(visible, 3000);
}

TEST(ZPyramid, OneFarPixelOnTheBorderOrInACornerIsFound)
{
    for (const auto &[w, h] : sizes) {
        const std::vector<std::pair<int, int>> spots{{0, 0}, {w - 1, 0}, {0, h - 1}, {w - 1, h - 1}, {w / 2, h - 1}, {w - 1, h / 2}};
        for (const auto &[fx, fy] : spots) {
            std::vector<float> d(std::size_t(w) * std::size_t(h), 0.25f);
            d[std::size_t(fy) * std::size_t(w) + std::size_t(fx)] = 0.75f;
            ZPyramid zp;
            zp.build(w, h, d.data());
            const PixelRect whole{0, 0, w, h}, beyond{-5, -5, w + 5, h + 5};
            EXPECT_FALSE(zp.occluded(whole, 0.5f)) << w << "x" << h << " far pixel " << fx << "," << fy;
            EXPECT_FALSE(zp.occluded(beyond, 0.5f)) << w << "x" << h << " far pixel " << fx << "," << fy;
            EXPECT_TRUE(zp.occluded(whole, 0.8f));
            EXPECT_FALSE(zp.occluded({fx, fy, fx + 1, fy + 1}, 0.5f));
            // Every rectangle reaching the image's edge beside the pixel but
            // leaving it out is occluded.
            if (fx > 0) {
                EXPECT_TRUE(zp.occluded({-3, -3, fx, h + 3}, 0.5f)) << w << "x" << h << " left of " << fx << "," << fy;
            }
            if (fx + 1 < w) {
                EXPECT_TRUE(zp.occluded({fx + 1, -3, w + 3, h + 3}, 0.5f)) << w << "x" << h << " right of " << fx;
            }
            if (fy > 0) {
                EXPECT_TRUE(zp.occluded({-3, -3, w + 3, fy}, 0.5f)) << w << "x" << h << " below " << fy;
            }
            if (fy + 1 < h) {
                EXPECT_TRUE(zp.occluded({-3, fy + 1, w + 3, h + 3}, 0.5f)) << w << "x" << h << " above " << fy;
            }
        }
    }
}

TEST(ZPyramid, EmptyOffImageAndUnbuiltGiveNotOccluded)
{
    ZPyramid zp;
    EXPECT_FALSE(zp.occluded({0, 0, 4, 4}, 0.5f));   // before any build
    const std::vector<float> d(13 * 5, 0.0f);
    zp.build(13, 5, d.data());
    EXPECT_TRUE(zp.occluded({0, 0, 13, 5}, 0.5f));
    EXPECT_FALSE(zp.occluded({3, 2, 3, 4}, 0.5f));      // empty
    EXPECT_FALSE(zp.occluded({13, 0, 20, 5}, 0.5f));    // right of the image
    EXPECT_FALSE(zp.occluded({-9, -9, 0, 0}, 0.5f));    // below left
    EXPECT_FALSE(zp.occluded({0, 0, 13, 5}, std::nanf("")));
    zp.build(0, 0, nullptr);
    EXPECT_EQ(zp.levels(), 0);
    EXPECT_FALSE(zp.occluded({0, 0, 4, 4}, 0.5f));
    EXPECT_THROW(zp.build(-1, 4, d.data()), std::invalid_argument);
}

TEST(ZPyramid, NaNDepthCountsAsFar)
{
    std::vector<float> d(7 * 7, 0.2f);
    d[3 * 7 + 5] = std::nanf("");
    ZPyramid zp;
    zp.build(7, 7, d.data());
    EXPECT_EQ(zp.level(0).at(5, 3), 1.0f);
    EXPECT_EQ(zp.level(zp.levels() - 1).at(0, 0), 1.0f);
    EXPECT_FALSE(zp.occluded({0, 0, 7, 7}, 0.9f));
    EXPECT_TRUE(zp.occluded({0, 0, 5, 7}, 0.9f));
}

TEST(ZPyramid, FewTexelsVisitedOverACoveredRegion)
{
    // 256x256, an occluder at 0.3 over [8, 248)^2, cleared around it.
    const int w = 256, h = 256;
    std::vector<float> d(std::size_t(w) * std::size_t(h), 1.0f);
    for (int y = 8; y < 248; ++y)
        for (int x = 8; x < 248; ++x)
            d[std::size_t(y) * std::size_t(w) + std::size_t(x)] = 0.3f;
    ZPyramid zp;
    zp.build(w, h, d.data());
    const PixelRect rect{40, 30, 220, 200};
    std::uint64_t visited = 0;
    EXPECT_TRUE(zp.occluded(rect, 0.5f, &visited));
    EXPECT_GT(visited, 0u);
    EXPECT_LT(visited * 50, std::uint64_t(rect.area())) << visited << " texels for " << rect.area() << " pixels";

    // A box nearer than the occluder: visible at the first texel compared?
    // Not necessarily the first, but long before the pixels run out.
    visited = 0;
    EXPECT_FALSE(zp.occluded(rect, 0.3f, &visited));
    EXPECT_LT(visited, 64u);

    // One pixel of the occluder missing: visible, found by descending only
    // where the texels are not nearer than z.
    d[std::size_t(150) * std::size_t(w) + 111] = 1.0f;
    zp.build(w, h, d.data());
    visited = 0;
    EXPECT_FALSE(zp.occluded(rect, 0.5f, &visited));
    EXPECT_LT(visited * 50, std::uint64_t(rect.area())) << visited;
}

TEST(ZPyramid, VisitCounterAddsUp)
{
    std::vector<float> d(16 * 16, 0.1f);
    ZPyramid zp;
    zp.build(16, 16, d.data());
    std::uint64_t visited = 0;
    zp.occluded({0, 0, 16, 16}, 0.5f, &visited);
    const std::uint64_t once = visited;
    EXPECT_EQ(once, 4u);   // the 2 x 2 texels of level 3 (8 x 8 pixels each) settle it
    zp.occluded({0, 0, 16, 16}, 0.5f, &visited);
    EXPECT_EQ(visited, 2 * once);
    // Nothing nearer than z: the descent reaches a level-0 pixel and stops.
    std::uint64_t to_pixel = 0;
    EXPECT_FALSE(zp.occluded({0, 0, 16, 16}, 0.05f, &to_pixel));
    EXPECT_EQ(to_pixel, 4u);   // one texel each of levels 3, 2, 1, 0
}

TEST(ZPyramid, RebuildReusesStorageAndForgetsThePreviousImage)
{
    std::mt19937 rng(23);
    std::vector<float> big = scene(300, 200, rng), small = scene(13, 5, rng);
    ZPyramid zp;
    zp.build(300, 200, big.data());
    const float *storage = zp.level(0).depth;
    zp.build(13, 5, small.data());
    EXPECT_EQ(zp.level(0).depth, storage);   // no reallocation
    zp.build(300, 200, big.data());
    EXPECT_EQ(zp.level(0).depth, storage);
    // The new image only: a near image after a far one.
    std::vector<float> near(300 * 200, 0.05f), far(300 * 200, 1.0f);
    zp.build(300, 200, far.data());
    EXPECT_FALSE(zp.occluded({0, 0, 300, 200}, 0.5f));
    zp.build(300, 200, near.data());
    EXPECT_TRUE(zp.occluded({0, 0, 300, 200}, 0.5f));
    EXPECT_EQ(zp.level(0).depth, storage);
}
