// SPDX-License-Identifier: MIT
// The box faces and front-face masks that shadow culling's geometries
// share (geometry/convex_region.h).
#include "geometry/convex_region.h"

#include <gtest/gtest.h>

using namespace occu;

TEST(ConvexRegion, BoxFacesWindOutwards)
{
    const Aabb c = Aabb::of({-1, 2, 3}, {4, 5, 7});
    for (int f = 0; f < 6; ++f) {
        const auto q = box_face(c, f);
        ASSERT_EQ(q.size(), 4u);
        glm::dvec3 newell(0.0);
        for (std::size_t i = 0; i < 4; ++i)
            newell += glm::cross(q[i], q[(i + 1) % 4]);
        EXPECT_GT(glm::dot(glm::normalize(newell), box_face_normal(f)), 0.999) << "face " << f;
        // The face lies on the box's surface.
        for (const glm::dvec3 &p : q)
            EXPECT_EQ(p[f / 2], f % 2 ? c.max[f / 2] : c.min[f / 2]);
    }
}

// The eye within the margin of a face's plane sees no certain set of
// faces; the eye inside sees none.
TEST(ConvexRegion, FrontFacesOfABox)
{
    const Aabb c = Aabb::of({0, 0, 0}, {4, 4, 4});
    EXPECT_FALSE(front_faces({4, 9, 9}, c, 1e-9));
    EXPECT_FALSE(front_faces({2, 2, 2}, c, 1e-9));
    ASSERT_TRUE(front_faces({2, 2, 9}, c, 1e-9));
    EXPECT_EQ(*front_faces({2, 2, 9}, c, 1e-9), 1u << 5);   // the max z face alone
}
