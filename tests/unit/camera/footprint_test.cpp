// SPDX-License-Identifier: MIT
// A box's footprint against brute force: every pixel whose centre a point
// of the box projects into lies inside the footprint (and inside its map
// rectangle at any divisor); boxes that hold the eye or cross the near
// plane, and non-finite boxes, have none.
#include "camera/footprint.h"

#include <gtest/gtest.h>

#include <cmath>
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
