// SPDX-License-Identifier: MIT
// The proxy an occlusion test draws for a box: grown by about 1.5 pixels
// at its distance, and refused where growing makes it hold the eye or
// cross the near plane (drawn with back faces culled and clipped there, it
// would lose the faces that cover the box's content).
#include "render/occlusion_proxy.h"

#include <gtest/gtest.h>

#include <cmath>

#include "camera/footprint.h"

using namespace occu;

namespace {
// At the origin looking down -z: 60 degrees, near plane 0.1 m.
Camera camera_at_origin()
{
    Camera c;
    c.position = {0, 0, 0};
    c.target = {0, 0, -1};
    c.near_plane = 0.1f;
    c.far_plane = 100.0f;
    return c;
}
}  // namespace

TEST(ProxyBox, GrowsByAboutOneAndAHalfPixelsAtTheBoxDistance)
{
    const Camera c = camera_at_origin();
    const Aabb box = Aabb::of({-1, -1, -12}, {1, 1, -10});
    const auto proxy = proxy_box(box, c, c.view_projection(), 128);
    ASSERT_TRUE(proxy);
    // A pixel at 10 m of a 128-pixel-high view of 60 degrees.
    const float pixel = 2.0f * std::tan(glm::radians(30.0f)) * 10.0f / 128.0f;
    EXPECT_NEAR(box.min.x - proxy->min.x, 1.5f * pixel, 0.02f);
    EXPECT_NEAR(proxy->max.z - box.max.z, 1.5f * pixel, 0.02f);
}

TEST(ProxyBox, IsEmptyWhereAPixelIsWiderThanTheDistanceAndTheGrownBoxHoldsTheEye)
{
    // One pixel of 60 degrees is 1.15 m wide at 1 m: the box grows by 1.7
    // times its distance.
    const Camera c = camera_at_origin();
    const Aabb box = Aabb::of({-1, -1, -12}, {1, 1, -10});
    ASSERT_TRUE(box_footprint(c.view_projection(), c.position, box, 1, 1)) << "the box itself is testable";
    EXPECT_FALSE(proxy_box(box, c, c.view_projection(), 1));
}

TEST(ProxyBox, IsEmptyWhenGrowingTakesItInFrontOfTheNearPlane)
{
    const Camera c = camera_at_origin();
    const Aabb box = Aabb::of({-0.5f, -0.5f, -1}, {0.5f, 0.5f, -0.105f});
    ASSERT_TRUE(box_footprint(c.view_projection(), c.position, box, 128, 128)) << "the box itself is testable";
    EXPECT_FALSE(proxy_box(box, c, c.view_projection(), 128));
}
