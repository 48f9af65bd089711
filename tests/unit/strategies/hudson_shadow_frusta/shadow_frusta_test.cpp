// SPDX-License-Identifier: MIT
// Hudson et al.'s shadow frusta (Moeller and Haines, "Occlusion Culling
// Algorithms", section "Shadow Culling"; shadow_frusta.h) against brute
// force: a box the tests call occluded has every sample point (its corners
// and random points inside) hidden, the segment from the eye to the point
// crossing the occluder (a convex polygon, or a box aggregate); a box whose
// corners are all hidden with room to spare is called occluded (the tests
// are exact, not merely conservative), on random convex polygons, eyes and
// boxes.
#include "strategies/hudson_shadow_frusta/shadow_frusta.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "../shadow_culling_samples.h"

using namespace occu;
using namespace occu::shadow_samples;

TEST(ShadowFrusta, PolygonShadowFrustaAreConservativeAndExact)
{
    Random r(20240611);
    int occluded = 0, missed = 0;
    for (int n = 0; n < trials; ++n) {
        const Polygon poly = random_polygon(r);
        const Viewing s = aimed_or_random(r, poly.centre, poly.normal, poly.u, poly.v, 4.0);
        const auto shadow = polygon_shadow(s.eye, poly.vertices);
        const bool claimed = shadow && shadow->holds(s.box);
        if (claimed) {
            ++occluded;
            for (const glm::dvec3 &p : samples(r, s.box, 32))
                ASSERT_TRUE(hidden_by_polygon(s.eye, p, poly.vertices)) << "trial " << n << ": a point is visible";
        } else {
            // The shadow is convex: corners hidden with room to spare mean
            // the box is hidden, and the test must say so.
            bool corners = true;
            for (int i = 0; i < 8 && corners; ++i)
                corners = robustly_hidden_by_polygon(s.eye, glm::dvec3(s.box.corner(i)), poly);
            missed += corners;
        }
    }
    EXPECT_GT(occluded, trials / 10) << "too few occluded boxes for the test to mean anything";
    EXPECT_EQ(missed, 0) << "boxes hidden by brute force that the shadow frustum did not hold";
    std::printf("polygon shadow frusta: %d of %d boxes occluded, %d missed\n", occluded, trials, missed);
}

TEST(ShadowFrusta, BoxAggregateShadowsAreConservativeAndExact)
{
    Random r(7);
    int occluded = 0, missed = 0, by_a_face = 0, only_aggregate = 0;
    for (int n = 0; n < trials; ++n) {
        const Aabb c = random_box(r, random_point(r, 10.0), 4.0);
        const glm::dvec3 centre(c.center()), u = random_unit(r);
        const glm::dvec3 normal = random_unit(r), v = glm::normalize(glm::cross(normal, u));
        const Viewing s = aimed_or_random(r, centre, normal, glm::normalize(glm::cross(v, normal)), v, 3.0);
        const auto shadow = box_shadow(s.eye, c);
        const bool claimed = shadow && shadow->holds(s.box);
        // The aggregate holds what each face the eye sees holds.
        bool face = false;
        for (int f = 0; f < 6; ++f) {
            if (glm::dot(box_face_normal(f), s.eye - box_face(c, f)[0]) <= 0.0)
                continue;
            const auto fs = polygon_shadow(s.eye, box_face(c, f));
            if (fs && fs->holds(s.box)) {
                face = true;
                EXPECT_TRUE(claimed) << "trial " << n << ": face " << f << " hides the box, its box does not";
            }
        }
        by_a_face += face;
        only_aggregate += claimed && !face;
        const glm::dvec3 lo(c.min), hi(c.max);
        if (claimed) {
            ++occluded;
            for (const glm::dvec3 &p : samples(r, s.box, 32))
                ASSERT_TRUE(hidden_by_box(s.eye, p, lo, hi)) << "trial " << n << ": a point is visible";
        } else {
            // (An eye inside the occluder sees nothing of it, by the
            // segment's rule; the shadow is of an occluder seen from outside.)
            const glm::dvec3 shrink = 1e-6 * (hi - lo);
            bool corners = !c.contains(glm::vec3(s.eye));
            for (int i = 0; i < 8 && corners; ++i)
                corners = hidden_by_box(s.eye, glm::dvec3(s.box.corner(i)), lo + shrink, hi - shrink);
            missed += corners;
        }
    }
    EXPECT_GT(occluded, trials / 10);
    EXPECT_EQ(missed, 0) << "boxes hidden by brute force that the box's shadow did not hold";
    EXPECT_GT(only_aggregate, trials / 100) << "the aggregate should hide boxes no single face hides";
    std::printf("box aggregate shadows: %d of %d boxes occluded (%d by a single face too, %d only by the aggregate), "
                "%d missed\n",
                occluded, trials, by_a_face, only_aggregate, missed);
}

// Degenerate input never claims occlusion: the eye on the occluder's
// plane, polygons without area or not convex, boxes touching the occluder.
TEST(ShadowFrusta, DegenerateCasesClaimNothing)
{
    const std::vector<glm::dvec3> square = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
    const Aabb behind = Aabb::of({1.5f, 1.5f, -3.0f}, {2.5f, 2.5f, -2.0f});
    const glm::dvec3 eye(2, 2, 5);
    ASSERT_TRUE(polygon_shadow(eye, square));
    EXPECT_TRUE(polygon_shadow(eye, square)->holds(behind));
    // Seen from behind the same square hides the box's mirror image.
    EXPECT_TRUE(polygon_shadow({2, 2, -5}, square)->holds(Aabb::of({1.5f, 1.5f, 2.0f}, {2.5f, 2.5f, 3.0f})));
    // The eye on the plane (or within the margin of it).
    EXPECT_FALSE(polygon_shadow({2, 2, 0}, square));
    EXPECT_FALSE(polygon_shadow({9, 2, 1e-12}, square));
    // No area: all vertices on a line, or repeated.
    EXPECT_FALSE(polygon_shadow(eye, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}));
    EXPECT_FALSE(polygon_shadow(eye, {{1, 1, 0}, {1, 1, 0}, {1, 1, 0}}));
    // Repeated vertices of a real polygon are harmless.
    const std::vector<glm::dvec3> repeated = {{0, 0, 0}, {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {4, 4, 0}, {0, 4, 0}};
    EXPECT_TRUE(polygon_shadow(eye, repeated) && polygon_shadow(eye, repeated)->holds(behind));
    // Not convex.
    EXPECT_FALSE(polygon_shadow(eye, {{0, 0, 0}, {4, 0, 0}, {1, 1, 0}, {0, 4, 0}}));
    // A box touching the polygon's plane from behind.
    EXPECT_FALSE(polygon_shadow(eye, square)->holds(Aabb::of({1.5f, 1.5f, -1.0f}, {2.5f, 2.5f, 0.0f})));
    // A box exactly in the shadow's boundary: its side reaches the plane
    // through the eye and an edge.
    EXPECT_FALSE(polygon_shadow({0, 2, 4}, square)->holds(Aabb::of({0.0f, 1.0f, -4.0f}, {1.0f, 2.0f, -3.0f})));
    EXPECT_TRUE(polygon_shadow({0, 2, 4}, square)->holds(Aabb::of({0.01f, 1.0f, -4.0f}, {1.0f, 2.0f, -3.0f})));
    // An empty box is never occluded.
    EXPECT_FALSE(polygon_shadow(eye, square)->holds(Aabb{}));

    // Box aggregates: the eye inside, on a face's plane, a flat occluder.
    const Aabb c = Aabb::of({0, 0, 0}, {4, 4, 4});
    EXPECT_FALSE(box_shadow({2, 2, 2}, c));
    EXPECT_FALSE(box_shadow({2, 2, 4}, c));
    EXPECT_FALSE(box_shadow({4, 9, 9}, c));
    EXPECT_FALSE(box_shadow({2, 2, 9}, Aabb::of({0, 0, 0}, {4, 4, 0})));
    ASSERT_TRUE(box_shadow({2, 2, 9}, c));
    EXPECT_TRUE(box_shadow({2, 2, 9}, c)->holds(Aabb::of({1.5f, 1.5f, -3.0f}, {2.5f, 2.5f, -2.0f})));
    // Inside the occluder itself counts as hidden (the segment reaches it),
    // but a box touching its front face does not.
    EXPECT_TRUE(box_shadow({2, 2, 9}, c)->holds(Aabb::of({1.5f, 1.5f, 1.0f}, {2.5f, 2.5f, 3.0f})));
    EXPECT_FALSE(box_shadow({2, 2, 9}, c)->holds(Aabb::of({1.5f, 1.5f, 1.0f}, {2.5f, 2.5f, 4.0f})));
}

// Far from the origin the margins grow with the coordinates and stay
// conservative: the same configuration a million metres away.
TEST(ShadowFrusta, FarFromTheOriginStillConservative)
{
    Random r(99);
    int occluded = 0;
    const glm::dvec3 offset(1e6, 0, -1e6);
    for (int n = 0; n < 2000; ++n) {
        Polygon poly = random_polygon(r);
        for (glm::dvec3 &v : poly.vertices)
            v = as_float(v + offset);
        poly.centre += offset;
        Viewing s = aimed_or_random(r, poly.centre, poly.normal, poly.u, poly.v, 4.0);
        const auto shadow = polygon_shadow(s.eye, poly.vertices);
        if (shadow && shadow->holds(s.box)) {
            ++occluded;
            for (const glm::dvec3 &p : samples(r, s.box, 16))
                ASSERT_TRUE(hidden_by_polygon(s.eye, p, poly.vertices)) << "trial " << n;
        }
    }
    EXPECT_GT(occluded, 100);
}
