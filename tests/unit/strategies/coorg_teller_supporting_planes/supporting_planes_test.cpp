// SPDX-License-Identifier: MIT
// Coorg and Teller's supporting planes (Moeller and Haines, "Occlusion
// Culling Algorithms", section "Shadow Culling"; supporting_planes.h): the
// test agrees with Hudson et al.'s shadow frusta (the equivalence
// supporting_planes.h states; the frusta are checked against brute force
// in hudson_shadow_frusta/shadow_frusta_test.cpp), and every box it calls
// occluded is hidden by brute force, on random convex polygons, eyes and
// boxes.
#include "strategies/coorg_teller_supporting_planes/supporting_planes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "../shadow_culling_samples.h"
#include "strategies/hudson_shadow_frusta/shadow_frusta.h"

using namespace occu;
using namespace occu::shadow_samples;

// Coorg and Teller's test (the viewer inside every supporting plane of an
// occluder and a box) and Hudson et al.'s (the box inside the occluder's
// shadow frustum) give the same answer for a single convex occluder, once
// the occluder's plane (an aggregate's front-face planes) is among the
// viewer's half-spaces and the box is required behind it: the supporting
// planes through the edges alone also hold viewers between the occluder
// and a box in front of it. Measured: no difference in 20000 random
// polygons and 20000 random box aggregates (2168 and 5586 boxes occluded
// by both); near the boundary see the next test.
TEST(SupportingPlanes, SupportingPlanesAgreeWithShadowFrusta)
{
    Random r(1997);
    int polygon_both = 0, polygon_differ = 0, box_both = 0, box_differ = 0;
    for (int n = 0; n < trials; ++n) {
        const Polygon poly = random_polygon(r);
        const Viewing s = aimed_or_random(r, poly.centre, poly.normal, poly.u, poly.v, 4.0);
        const auto shadow = polygon_shadow(s.eye, poly.vertices);
        const auto planes = polygon_supporting_planes(poly.vertices, s.box);
        const bool hudson = shadow && shadow->holds(s.box), coorg = planes && planes->holds(s.eye);
        polygon_both += hudson && coorg;
        polygon_differ += hudson != coorg;
        if (coorg) {
            for (const glm::dvec3 &p : samples(r, s.box, 16))
                ASSERT_TRUE(hidden_by_polygon(s.eye, p, poly.vertices)) << "trial " << n;
        }
    }
    for (int n = 0; n < trials; ++n) {
        const Aabb c = random_box(r, random_point(r, 10.0), 4.0);
        const glm::dvec3 normal = random_unit(r), u = glm::normalize(glm::cross(normal, random_unit(r)));
        const Viewing s = aimed_or_random(r, glm::dvec3(c.center()), normal, u, glm::cross(normal, u), 3.0);
        const auto shadow = box_shadow(s.eye, c);
        const auto front = front_faces(s.eye, c, shadow_margin(std::max(magnitude(s.eye), magnitude(c))));
        const auto planes = front ? box_supporting_planes(c, *front, s.box) : std::nullopt;
        const bool hudson = shadow && shadow->holds(s.box), coorg = planes && planes->holds(s.eye);
        box_both += hudson && coorg;
        box_differ += hudson != coorg;
        if (coorg) {
            for (const glm::dvec3 &p : samples(r, s.box, 16))
                ASSERT_TRUE(hidden_by_box(s.eye, p, glm::dvec3(c.min), glm::dvec3(c.max))) << "trial " << n;
        }
    }
    EXPECT_GT(polygon_both, trials / 10);
    EXPECT_GT(box_both, trials / 10);
    EXPECT_EQ(polygon_differ, 0);
    EXPECT_EQ(box_differ, 0);
    std::printf("supporting planes vs shadow frusta: polygons %d occluded by both, %d differ; "
                "box aggregates %d by both, %d differ (of %d each)\n",
                polygon_both, polygon_differ, box_both, box_differ, trials);
}

// The same near the boundary, where a difference would show: an eye that
// sees the box hidden moved towards one that does not, bisected to the
// shadow frustum's boundary, then set a micrometre to either side. The
// two tests measure different distances (box corners from side planes,
// the eye from supporting planes), so within their margins (about 1e-8 m
// here) one may refuse what the other just accepts; without the margins
// (the exact predicates: every distance positive) they agree.
TEST(SupportingPlanes, SupportingPlanesAgreeWithShadowFrustaAtTheBoundary)
{
    Random r(83);
    int probes = 0, exact_differ = 0, margin_differ = 0;
    for (int n = 0; n < trials && probes < 2000; ++n) {
        const Polygon poly = random_polygon(r);
        const Viewing s = aimed_or_random(r, poly.centre, poly.normal, poly.u, poly.v, 4.0);
        const auto planes = polygon_supporting_planes(poly.vertices, s.box);
        auto hudson = [&](const glm::dvec3 &eye) {
            const auto shadow = polygon_shadow(eye, poly.vertices);
            return shadow && shadow->holds(s.box);
        };
        if (!planes || !hudson(s.eye))
            continue;
        glm::dvec3 in = s.eye, out = s.eye + 60.0 * random_unit(r);
        if (hudson(out))
            continue;
        for (int i = 0; i < 60; ++i) {
            const glm::dvec3 mid = 0.5 * (in + out);
            (hudson(mid) ? in : out) = mid;
        }
        const glm::dvec3 step = 1e-6 * glm::normalize(out - in);
        for (const glm::dvec3 &eye : {in - step, out + step}) {
            ++probes;
            margin_differ += hudson(eye) != planes->holds(eye);
            // The exact predicates: the smallest distance of each test.
            const auto shadow = polygon_shadow(eye, poly.vertices);
            if (!shadow)
                continue;   // the eye within the margin of the plane: both refuse
            double box_inside = 1e30, eye_inside = 1e30;
            for (int i = 0; i < shadow->count; ++i)
                box_inside = std::min(box_inside, shadow->planes[std::size_t(i)].min_distance(s.box));
            for (int i = 0; i < planes->count; ++i)
                eye_inside = std::min(eye_inside, planes->planes[std::size_t(i)].distance(eye));
            if (std::fabs(box_inside) > 1e-12 && std::fabs(eye_inside) > 1e-12)
                exact_differ += (box_inside > 0.0) != (eye_inside > 0.0);
        }
    }
    EXPECT_GT(probes, 1000);
    EXPECT_EQ(exact_differ, 0);
    EXPECT_LT(margin_differ, probes / 20);
    std::printf("at the boundary, polygons: %d probes a micrometre from it; the exact predicates differ in %d, "
                "the tests with their margins in %d\n",
                probes, exact_differ, margin_differ);

    // Box aggregates: the supporting planes of the region the eye is in.
    int box_probes = 0, box_exact_differ = 0, box_margin_differ = 0;
    for (int n = 0; n < trials && box_probes < 2000; ++n) {
        const Aabb c = random_box(r, random_point(r, 10.0), 4.0);
        const glm::dvec3 normal = random_unit(r), u = glm::normalize(glm::cross(normal, random_unit(r)));
        const Viewing s = aimed_or_random(r, glm::dvec3(c.center()), normal, u, glm::cross(normal, u), 3.0);
        auto hudson = [&](const glm::dvec3 &eye) {
            const auto shadow = box_shadow(eye, c);
            return shadow && shadow->holds(s.box);
        };
        if (!hudson(s.eye))
            continue;
        glm::dvec3 in = s.eye, out = s.eye + 60.0 * random_unit(r);
        if (hudson(out))
            continue;
        for (int i = 0; i < 60; ++i) {
            const glm::dvec3 mid = 0.5 * (in + out);
            (hudson(mid) ? in : out) = mid;
        }
        const glm::dvec3 step = 1e-6 * glm::normalize(out - in);
        for (const glm::dvec3 &eye : {in - step, out + step}) {
            const auto shadow = box_shadow(eye, c);
            const auto front = front_faces(eye, c, shadow_margin(std::max(magnitude(eye), magnitude(c))));
            const auto planes = front ? box_supporting_planes(c, *front, s.box) : std::nullopt;
            ++box_probes;
            box_margin_differ += hudson(eye) != (planes && planes->holds(eye));
            if (!shadow || !planes)
                continue;   // the eye on a face's plane, or the box not behind the front faces: both refuse
            double box_inside = 1e30, eye_inside = 1e30;
            for (int i = 0; i < shadow->count; ++i)
                box_inside = std::min(box_inside, shadow->planes[std::size_t(i)].min_distance(s.box));
            for (int i = 0; i < planes->count; ++i)
                eye_inside = std::min(eye_inside, planes->planes[std::size_t(i)].distance(eye));
            if (std::fabs(box_inside) > 1e-12 && std::fabs(eye_inside) > 1e-12)
                box_exact_differ += (box_inside > 0.0) != (eye_inside > 0.0);
        }
    }
    EXPECT_GT(box_probes, 1000);
    EXPECT_EQ(box_exact_differ, 0);
    EXPECT_LT(box_margin_differ, box_probes / 20);
    std::printf("at the boundary, box aggregates: %d probes; the exact predicates differ in %d, "
                "the tests with their margins in %d\n",
                box_probes, box_exact_differ, box_margin_differ);
}

// Degenerate input never claims occlusion: the eye on the occluder's
// plane, polygons without area, boxes touching the occluder, masks that
// are no region of viewpoints.
TEST(SupportingPlanes, DegenerateCasesClaimNothing)
{
    const std::vector<glm::dvec3> square = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
    const Aabb behind = Aabb::of({1.5f, 1.5f, -3.0f}, {2.5f, 2.5f, -2.0f});
    const glm::dvec3 eye(2, 2, 5);
    EXPECT_TRUE(polygon_supporting_planes(square, behind)->holds(eye));
    // The eye on the plane.
    EXPECT_FALSE(polygon_supporting_planes(square, behind)->holds({9, 2, 0}));
    // No area: all vertices on a line.
    EXPECT_FALSE(polygon_supporting_planes({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, behind));
    // A box touching the polygon's plane from behind, or crossing it.
    EXPECT_FALSE(polygon_supporting_planes(square, Aabb::of({1.5f, 1.5f, -1.0f}, {2.5f, 2.5f, 0.0f})));
    EXPECT_FALSE(polygon_supporting_planes(square, Aabb::of({1.5f, 1.5f, -1.0f}, {2.5f, 2.5f, 1.0f})));

    // Box aggregates: a box touching the front face.
    const Aabb c = Aabb::of({0, 0, 0}, {4, 4, 4});
    EXPECT_FALSE(box_supporting_planes(c, *front_faces({2, 2, 9}, c, 1e-9),
                                       Aabb::of({1.5f, 1.5f, 1.0f}, {2.5f, 2.5f, 4.0f})));
    // A mask that sees both faces of an axis, or none, is no region.
    EXPECT_FALSE(box_supporting_planes(c, 3u, Aabb::of({1, 1, 9}, {2, 2, 10})));
    EXPECT_FALSE(box_supporting_planes(c, 0u, Aabb::of({1, 1, 9}, {2, 2, 10})));
}
