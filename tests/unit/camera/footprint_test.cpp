// SPDX-License-Identifier: MIT
// A box's footprint against brute force: every pixel whose centre a point
// of the box projects into lies inside the footprint (and inside its map
// rectangle at any divisor); boxes that hold the eye or cross the near
// plane, and non-finite boxes, have none.
#include "camera/footprint.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

using namespace occu;

namespace {

// Window pixel of a world point, or false behind the eye.
bool pixel_of(const glm::mat4 &vp, const glm::vec3 &p, int w, int h, int &x, int &y)
{
    const glm::vec4 c = vp * glm::vec4(p, 1.0f);
    if (c.w <= 0.0f)
        return false;
    x = int(std::floor((c.x / c.w + 1.0f) * 0.5f * float(w)));
    y = int(std::floor((c.y / c.w + 1.0f) * 0.5f * float(h)));
    return true;
}

}  // namespace

TEST(Footprint, HoldsEveryPixelThatPointsOfTheBoxProjectTo)
{
    std::mt19937 random(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Camera camera;
    camera.position = {0, 0, 0};
    camera.target = {0, 0, -1};
    const glm::mat4 vp = camera.view_projection();
    const int w = 97, h = 61;
    int tested = 0;
    for (int i = 0; i < 300; ++i) {
        const glm::vec3 centre(6.0f * u(random), 6.0f * u(random), -8.0f + 6.0f * u(random));
        const glm::vec3 half(0.05f + 1.5f * std::abs(u(random)), 0.05f + 1.5f * std::abs(u(random)),
                             0.05f + 1.5f * std::abs(u(random)));
        const Aabb box = Aabb::of(centre - half, centre + half);
        const auto f = box_footprint(vp, camera.position, box, w, h);
        if (!f)
            continue;
        ++tested;
        for (int k : {1, 2, 4, 7}) {
            const PixelRect m = f->rect.to_map(k);
            for (int s = 0; s < 400; ++s) {
                const glm::vec3 p = centre + half * glm::vec3(u(random), u(random), u(random));
                int x, y;
                if (!pixel_of(vp, p, w, h, x, y) || x < 0 || y < 0 || x >= w || y >= h)
                    continue;
                ASSERT_TRUE(x >= f->rect.x0 && x < f->rect.x1 && y >= f->rect.y0 && y < f->rect.y1)
                    << "box " << i << " pixel " << x << "," << y;
                ASSERT_TRUE(x / k >= m.x0 && x / k < m.x1 && y / k >= m.y0 && y / k < m.y1) << "divisor " << k;
                const glm::vec4 c = vp * glm::vec4(p, 1.0f);
                EXPECT_LE(f->window_z_near, 0.5f * (c.z / c.w) + 0.5f + 1e-6f);
            }
        }
    }
    EXPECT_GT(tested, 100);
}

TEST(Footprint, NoneForTheEyeInsideTheNearPlaneCrossedOrNonFiniteBoxes)
{
    Camera camera;
    camera.position = {0, 0, 0};
    camera.target = {0, 0, -1};
    const glm::mat4 vp = camera.view_projection();
    EXPECT_FALSE(box_footprint(vp, camera.position, Aabb::of({-1, -1, -1}, {1, 1, 1}), 64, 64));
    EXPECT_FALSE(box_footprint(vp, camera.position, Aabb::of({-1, -1, -5}, {1, 1, -0.1f}), 64, 64));
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_FALSE(box_footprint(vp, camera.position, Aabb::of({-1, -1, -inf}, {1, 1, -5}), 64, 64));
    EXPECT_FALSE(box_footprint(vp, camera.position, Aabb::of({-1, -1, std::nanf("")}, {1, 1, -5}), 64, 64));
    const auto ahead = box_footprint(vp, camera.position, Aabb::of({-1, -1, -6}, {1, 1, -5}), 64, 64);
    ASSERT_TRUE(ahead);
    EXPECT_FALSE(ahead->rect.empty());
    // Far off to the side: inside the viewport's bounds, empty.
    const auto aside = box_footprint(vp, camera.position, Aabb::of({1e6f, -1, -6}, {1e6f + 1, 1, -5}), 64, 64);
    ASSERT_TRUE(aside);
    EXPECT_TRUE(aside->rect.empty());
}

// box_footprint's kernels agree bit for bit: real cameras near and far from
// the origin, and matrices and boxes with zeros of both signs, infinities,
// NaN and huge entries (the corner-by-corner fold's ties, NaN corners and
// overflowing windows), in viewports of many sizes.
TEST(Footprint, Avx2KernelEqualsScalarBitForBit)
{
    if (!__builtin_cpu_supports("avx2"))
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar kernel runs here";
    const auto bits = [](float f) {
        std::uint32_t u;
        std::memcpy(&u, &f, sizeof u);
        return u;
    };
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, inf, -inf, nan, 1e30f, -1e30f, 3e38f, 1e-40f};
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(-1, 1), size(0.001f, 1), fov(20, 120);
    std::uniform_int_distribution<int> pick(0, 31), viewport(1, 2048);
    // A random entry, now and then a special one.
    const auto entry = [&](float value) {
        const int k = pick(rng);
        return k < int(std::size(specials)) ? specials[k] : value;
    };
    int footprints = 0, none = 0, clipped = 0;
    for (int i = 0; i < 200000; ++i) {
        Camera c;
        const float scale = std::pow(10.0f, float(i % 7));
        c.position = glm::vec3(unit(rng), unit(rng), unit(rng)) * scale;
        c.target = c.position + glm::vec3(unit(rng), unit(rng), unit(rng));
        c.fovy_degrees = fov(rng);
        c.aspect = 0.5f + size(rng);
        glm::mat4 vp = c.view_projection();
        const glm::vec3 lo = c.position + glm::vec3(unit(rng), unit(rng), unit(rng)) * 50.0f;
        Aabb box = Aabb::of(lo, lo + glm::vec3(size(rng), size(rng), size(rng)) * 30.0f);
        if (i % 4 == 1) {
            // Special entries in the matrix and the box.
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b)
                    vp[a][b] = entry(vp[a][b]);
            for (int a = 0; a < 3; ++a) {
                box.min[a] = entry(box.min[a]);
                box.max[a] = entry(box.max[a]);
            }
        } else if (i % 4 == 2) {
            // Corners on the axes: zeros of both signs in the products.
            for (int a = 0; a < 3; ++a) {
                if (pick(rng) < 8)
                    box.min[a] = pick(rng) < 16 ? 0.0f : -0.0f;
                if (pick(rng) < 8)
                    box.max[a] = pick(rng) < 16 ? 0.0f : -0.0f;
            }
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b)
                    if (pick(rng) < 4)
                        vp[a][b] = pick(rng) < 16 ? 0.0f : -0.0f;
        }
        const int w = i % 3 ? 512 : viewport(rng), h = i % 3 ? 512 : viewport(rng);
        const auto expected = box_footprint_scalar(vp, c.position, box, w, h);
        const auto got = box_footprint_avx2(vp, c.position, box, w, h);
        ASSERT_EQ(bool(expected), bool(got)) << "box " << i;
        if (!expected) {
            ++none;
            continue;
        }
        ++footprints;
        clipped += expected->rect.empty() || expected->rect.x0 == 0 || expected->rect.x1 == w;
        ASSERT_EQ(got->rect, expected->rect) << "box " << i;
        ASSERT_EQ(bits(got->window_z_near), bits(expected->window_z_near)) << "box " << i;
    }
    EXPECT_GT(footprints, 50000);
    EXPECT_GT(none, 20000);
    EXPECT_GT(clipped, 5000);
}

TEST(PixelRect, ToMapCoversEveryPixel)
{
    for (int k = 1; k <= 5; ++k)
        for (int x0 = -3; x0 < 9; ++x0)
            for (int x1 = x0; x1 < 12; ++x1) {
                const PixelRect m = PixelRect{x0, 0, x1, 1}.to_map(k);
                for (int x = x0; x < x1; ++x) {
                    const int mx = int(std::floor(double(x) / k));
                    EXPECT_TRUE(mx >= m.x0 && mx < m.x1) << k << " " << x0 << " " << x1;
                }
                EXPECT_LE(m.x1 - m.x0, (x1 - x0 + 2 * k - 2) / k + 1);
            }
}
