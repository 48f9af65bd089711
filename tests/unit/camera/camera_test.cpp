// SPDX-License-Identifier: MIT
// A camera's view matrix for every view direction: with the up vector
// parallel to the view direction (looking straight down or up with the
// default up), the cross product lookAt builds its basis from is zero.
#include "camera/camera.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace occu;

namespace {
bool finite(const glm::mat4 &m)
{
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r]))
                return false;
    return true;
}

// Normalized device coordinates of `p` seen by `camera`.
glm::vec3 ndc(const Camera &camera, const glm::vec3 &p)
{
    const glm::vec4 c = camera.view_projection() * glm::vec4(p, 1.0f);
    return glm::vec3(c) / c.w;
}

Camera looking_from(const glm::vec3 &position, const glm::vec3 &target)
{
    Camera c;
    c.position = position;
    c.target = target;
    c.near_plane = 0.1f;
    c.far_plane = 100.0f;
    return c;
}
}  // namespace

TEST(CameraView, LookingStraightDownIsFiniteAndCentresTheTarget)
{
    const Camera c = looking_from({3, 10, -2}, {3, 0, -2});
    ASSERT_TRUE(finite(c.view()));
    const glm::vec3 centre = ndc(c, c.target);
    EXPECT_NEAR(centre.x, 0.0f, 1e-6f);
    EXPECT_NEAR(centre.y, 0.0f, 1e-6f);
    EXPECT_GT(centre.z, -1.0f);
    EXPECT_LT(centre.z, 1.0f);
}

TEST(CameraView, LookingStraightUpIsFiniteAndCentresTheTarget)
{
    const Camera c = looking_from({0, -5, 0}, {0, 20, 0});
    ASSERT_TRUE(finite(c.view()));
    const glm::vec3 centre = ndc(c, c.target);
    EXPECT_NEAR(centre.x, 0.0f, 1e-6f);
    EXPECT_NEAR(centre.y, 0.0f, 1e-6f);
}

TEST(CameraView, LookingStraightDownKeepsARightHandedOrthonormalBasis)
{
    // A mirrored or sheared view would turn counter-clockwise faces into
    // clockwise ones, and back-face culling would drop the visible side.
    const glm::mat3 rotation(looking_from({0, 10, 0}, {0, 0, 0}).view());
    EXPECT_NEAR(glm::determinant(rotation), 1.0f, 1e-5f);
    const glm::mat3 product = glm::transpose(rotation) * rotation;
    float largest_error = 0.0f;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            largest_error = std::fmax(largest_error, std::fabs(product[c][r] - (c == r ? 1.0f : 0.0f)));
    EXPECT_LT(largest_error, 1e-5f) << "rotation^T rotation is not the identity";
}

TEST(CameraView, AnUpVectorAwayFromTheViewDirectionIsKept)
{
    // A view just off vertical keeps the given up: the image's top is the
    // side of +y, so a point above the target is above the centre.
    Camera c = looking_from({0, 1.7f, 0}, {0, 1.7f, -10});
    EXPECT_GT(ndc(c, {0, 3, -10}).y, 0.0f);
    c = looking_from({0, 10, 0}, {0.05f, 0, 0});
    EXPECT_GT(ndc(c, {1, 0, 0}).y, 0.0f) << "the image's top faces +x, where up tilts towards";
}
