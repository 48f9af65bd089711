// SPDX-License-Identifier: MIT
// View cells and occluder shrinking (Wonka, Wimmer and Schmalstieg 2000,
// sections 3 and 4.4; strategies/wonka_view_cells/view_cells.h and
// footprint_shrinking.h), each against brute force: the cells tile the free
// space exactly, with edges no longer than asked; locate() finds the triangle
// that holds a point; sample points leave no point of a top edge farther than
// epsilon; shrunk footprints keep only points at least epsilon deep in the
// original, and all points deeper than that (plus the join's slack), for
// convex, concave (L), courtyard and thin footprints.
#include "strategies/wonka_view_cells/view_cells.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "scene/city.h"
#include "strategies/wonka_view_cells/footprint_shrinking.h"

using namespace occu;

namespace {

PrismOccluder rectangle(double x0, double z0, double x1, double z1, double top = 20.0)
{
    PrismOccluder f;
    f.outline = {{x0, z0}, {x1, z0}, {x1, z1}, {x0, z1}};
    f.top = top;
    return f;
}

PrismOccluder l_shape()
{
    PrismOccluder f;
    f.outline = {{0, 0}, {30, 0}, {30, 10}, {10, 10}, {10, 30}, {0, 30}};
    f.top = 15.0;
    return f;
}

PrismOccluder courtyard()
{
    PrismOccluder f = rectangle(40, 40, 80, 80);
    f.holes = {{{50, 50}, {50, 70}, {70, 70}, {70, 50}}};
    return f;
}

double area(const PrismOccluder &f)
{
    double a = signed_area(f.outline);
    for (const auto &h : f.holes)
        a += signed_area(h);   // holes run clockwise: negative
    return a;
}

double triangle_area(const std::array<glm::dvec2, 3> &t)
{
    return 0.5 * ((t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[1].y - t[0].y) * (t[2].x - t[0].x));
}

}  // namespace

TEST(PrismOccluderShrinking, KeepsExactlyThePointsEpsilonDeep)
{
    std::mt19937 rng(3);
    for (const PrismOccluder &f : {rectangle(0, 0, 20, 12), l_shape(), courtyard()}) {
        for (double eps : {0.5, 1.0, 2.5}) {
            const std::vector<PrismOccluder> parts = shrink_footprint(f, eps);
            ASSERT_FALSE(parts.empty());
            for (const PrismOccluder &p : parts) {
                EXPECT_EQ(p.top, f.top);
                EXPECT_GT(signed_area(p.outline), 0.0) << "outline counter-clockwise";
                for (const auto &h : p.holes)
                    EXPECT_LT(signed_area(h), 0.0) << "holes clockwise";
            }
            std::uniform_real_distribution<double> u(-5.0, 90.0);
            int deep_points = 0;
            for (int i = 0; i < 20000; ++i) {
                const glm::dvec2 q(u(rng), u(rng));
                bool in_part = false;
                for (const PrismOccluder &p : parts)
                    in_part |= inside(p, q);
                const double depth = depth_inside(f, q);
                if (in_part)
                    EXPECT_GE(depth, eps - 1e-4) << "(" << q.x << ", " << q.y << ") is in the shrunk footprint, only "
                                                 << depth << " m deep in the original (epsilon " << eps << ")";
                // Square joins cut reflex corners by at most (sqrt(2) - 1) epsilon more than the arc.
                if (depth > eps * std::sqrt(2.0) + 1e-3) {
                    ++deep_points;
                    EXPECT_TRUE(in_part) << "(" << q.x << ", " << q.y << ") is " << depth << " m deep but was shrunk away";
                }
            }
            EXPECT_GT(deep_points, 100);
        }
    }
}

TEST(PrismOccluderShrinking, CourtyardsStayHolesAndThinOccludersVanish)
{
    const std::vector<PrismOccluder> ring = shrink_footprint(courtyard(), 1.0);
    ASSERT_EQ(ring.size(), 1u);
    ASSERT_EQ(ring[0].holes.size(), 1u) << "the courtyard stays a hole, grown by epsilon";
    // Between a square 22 m hole and the exact erosion (its corners
    // rounded with radius 1: 4 (1 - pi / 4) m^2 more ring), square joins
    // cutting the corners in between.
    EXPECT_GT(area(ring[0]), 38.0 * 38.0 - 22.0 * 22.0);
    EXPECT_LT(area(ring[0]), 38.0 * 38.0 - 22.0 * 22.0 + 4.0 * (1.0 - std::acos(-1.0) / 4.0));
    EXPECT_TRUE(shrink_footprint(rectangle(0, 0, 100, 1.5), 1.0).empty()) << "1.5 m thick, shrunk by 1 m each side";
    // Two squares joined by a corridor 1 m wide split into two.
    PrismOccluder dumbbell;
    dumbbell.outline = {{0, 0}, {10, 0}, {10, 4.5}, {20, 4.5}, {20, 0}, {30, 0}, {30, 10}, {20, 10}, {20, 5.5}, {10, 5.5}, {10, 10}, {0, 10}};
    EXPECT_EQ(shrink_footprint(dumbbell, 1.0).size(), 2u);
    EXPECT_THROW(shrink_footprint(rectangle(0, 0, 1, 1), std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    EXPECT_THROW(shrink_footprint(rectangle(0, 0, 1, 1), -1.0), std::invalid_argument);
    PrismOccluder bad = rectangle(0, 0, 1, 1);
    bad.outline[2].x = std::numeric_limits<double>::infinity();
    EXPECT_THROW(shrink_footprint(bad, 1.0), std::invalid_argument);
}

TEST(ViewCells, TileTheFreeSpaceWithShortEdges)
{
    const std::vector<PrismOccluder> occluders = {l_shape(), courtyard(), rectangle(100, 10, 130, 25)};
    // Without clearance (and no slits closed) the cells are exactly the ground less the footprints.
    {
        ViewCellOptions o;
        o.max_edge = 12.0;
        o.clearance = 0.0;
        o.close_gaps = 0.0;
        const ViewCells cells({-20, -20}, {160, 120}, occluders, o);
        double free_area = 180.0 * 140.0, cell_area = 0.0;
        for (const PrismOccluder &f : occluders)
            free_area -= area(f);
        for (std::size_t i = 0; i < cells.size(); ++i)
            cell_area += triangle_area(cells.triangle(i));
        // Up to Clipper's grid: holes grown by one 0.1 mm unit, times a perimeter of about 450 m.
        EXPECT_NEAR(cell_area, free_area, 0.1) << "the cells are exactly the free space";
    }
    ViewCellOptions o;
    o.max_edge = 12.0;
    o.clearance = 1.5;
    const ViewCells cells({-20, -20}, {160, 120}, occluders, o);
    double free_area = 180.0 * 140.0;
    for (const PrismOccluder &f : grown_union(occluders, o.clearance, o.close_gaps))
        free_area -= area(f);
    double cell_area = 0.0;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const auto &t = cells.triangle(i);
        EXPECT_GT(triangle_area(t), 0.0) << "counter-clockwise, not degenerate";
        cell_area += triangle_area(t);
        for (int e = 0; e < 3; ++e)
            EXPECT_LE(glm::length(t[std::size_t((e + 1) % 3)] - t[std::size_t(e)]), o.max_edge + 1e-9);
        // Every corner keeps the clearance from every footprint (and so
        // every point: the footprints grown by it are the cells' holes).
        for (const glm::dvec2 &p : t)
            for (const PrismOccluder &f : occluders) {
                EXPECT_FALSE(inside(f, p)) << "cell " << i << " corner in an occluder";
                double nearest = 1e300;
                for (std::size_t a = 0, b = f.outline.size() - 1; a < f.outline.size(); b = a++) {
                    const glm::dvec2 u = f.outline[b], v = f.outline[a], uv = v - u;
                    const double tt = std::clamp(glm::dot(p - u, uv) / glm::dot(uv, uv), 0.0, 1.0);
                    nearest = std::min(nearest, glm::length(p - (u + tt * uv)));
                }
                for (const auto &hole : f.holes)
                    for (std::size_t a = 0, b = hole.size() - 1; a < hole.size(); b = a++) {
                        const glm::dvec2 u = hole[b], v = hole[a], uv = v - u;
                        const double tt = std::clamp(glm::dot(p - u, uv) / glm::dot(uv, uv), 0.0, 1.0);
                        nearest = std::min(nearest, glm::length(p - (u + tt * uv)));
                    }
                EXPECT_GE(nearest, o.clearance - 1e-3) << "cell " << i << " corner (" << p.x << ", " << p.y << ")";
            }
    }
    EXPECT_NEAR(cell_area, free_area, 1e-6 * free_area) << "the cells are exactly the free space with its clearance";

    // locate() against every triangle.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> ux(-25.0, 165.0), uz(-25.0, 125.0), uy(-1.0, 3.0);
    int located = 0, in_courtyard = 0;
    for (int i = 0; i < 5000; ++i) {
        const glm::vec3 eye(float(ux(rng)), float(uy(rng)), float(uz(rng)));
        const glm::dvec2 p(eye.x, eye.z);
        bool in_some = false;
        for (std::size_t c = 0; c < cells.size() && !in_some; ++c) {
            const auto &t = cells.triangle(c);
            auto side = [&](int a, int b) {
                const glm::dvec2 e = t[std::size_t(b)] - t[std::size_t(a)], q = p - t[std::size_t(a)];
                return e.x * q.y - e.y * q.x;
            };
            in_some = side(0, 1) >= 0 && side(1, 2) >= 0 && side(2, 0) >= 0;
        }
        const bool in_height = eye.y >= o.bottom && eye.y <= o.top;
        const std::optional<std::uint32_t> c = cells.locate(eye);
        EXPECT_EQ(c.has_value(), in_some && in_height) << "(" << eye.x << ", " << eye.y << ", " << eye.z << ")";
        located += c.has_value();
        in_courtyard += c.has_value() && p.x > 52 && p.x < 68 && p.y > 52 && p.y < 68;
    }
    EXPECT_GT(located, 1000);
    EXPECT_GT(in_courtyard, 5) << "the courtyard is free space";
    EXPECT_FALSE(cells.locate({25.0f, 1.0f, 5.0f})) << "inside the L";
    EXPECT_FALSE(cells.locate({25.0f, 1.0f, -1.0f})) << "within the clearance of the L";
    EXPECT_FALSE(cells.locate({0.0f, 1.0f, std::numeric_limits<float>::quiet_NaN()}));
}

TEST(ViewCells, SamplePointsLeaveNoEdgePointFartherThanEpsilon)
{
    ViewCellOptions o;
    o.max_edge = 30.0;
    const ViewCells cells({0, 0}, {100, 100}, {rectangle(40, 40, 60, 60)}, o);
    for (double eps : {0.5, 1.0, 4.0})
        for (std::size_t c = 0; c < cells.size(); ++c) {
            const std::vector<glm::dvec3> samples = cells.sample_points(c, eps);
            const auto &t = cells.triangle(c);
            for (int e = 0; e < 3; ++e)
                for (int k = 0; k <= 200; ++k) {
                    const glm::dvec2 p = t[std::size_t(e)] + (t[std::size_t((e + 1) % 3)] - t[std::size_t(e)]) * (k / 200.0);
                    double nearest = std::numeric_limits<double>::infinity();
                    for (const glm::dvec3 &s : samples) {
                        EXPECT_EQ(s.y, o.top) << "samples lie on the top triangle";
                        nearest = std::min(nearest, glm::length(glm::dvec2(s.x, s.z) - p));
                    }
                    EXPECT_LE(nearest, eps + 1e-9) << "cell " << c << " edge " << e;
                }
        }
    EXPECT_THROW(cells.sample_points(0, 0.0), std::invalid_argument);
}

TEST(ViewCells, RefuseBadInput)
{
    ViewCellOptions o;
    EXPECT_THROW(ViewCells({0, 0}, {0, 10}, {}, o), std::invalid_argument);
    EXPECT_THROW(ViewCells({0, 0}, {std::numeric_limits<double>::infinity(), 10}, {}, o), std::invalid_argument);
    o.max_edge = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(ViewCells({0, 0}, {10, 10}, {}, o), std::invalid_argument);
    o.max_edge = 0.001;
    EXPECT_THROW(ViewCells({0, 0}, {1000, 1000}, {}, o), std::invalid_argument);
    o.max_edge = 10.0;
    o.top = o.bottom;
    EXPECT_THROW(ViewCells({0, 0}, {10, 10}, {}, o), std::invalid_argument);
    o = ViewCellOptions{};
    o.clearance = -1.0;
    EXPECT_THROW(ViewCells({0, 0}, {10, 10}, {}, o), std::invalid_argument);
    EXPECT_THROW(ViewCells(std::vector<std::array<glm::dvec2, 3>>{{glm::dvec2(0), glm::dvec2(1), glm::dvec2(2)}},
                           ViewCellOptions{}),
                 std::invalid_argument)
        << "a degenerate cell";
}

TEST(ViewCells, CoverTheCitysStreets)
{
    CityOptions city;
    city.blocks_x = city.blocks_z = 3;
    const Scene scene = generate_city(city);
    ASSERT_EQ(scene.prism_occluders.size(), std::size_t(9 * 12)) << "a ring of 12 buildings per block";
    const ViewCells cells({scene.bounds.min.x, scene.bounds.min.z}, {scene.bounds.max.x, scene.bounds.max.z},
                          scene.prism_occluders, ViewCellOptions{});
    EXPECT_TRUE(cells.locate({40.0f, 1.7f, 4.0f})) << "a street";
    const PrismOccluder &first = scene.prism_occluders.front();   // the lower left building of the first block
    EXPECT_FALSE(cells.locate({float(first.outline[0].x) + 3.0f, 1.7f, float(first.outline[0].y) - 0.5f}))
        << "within the clearance of a building";
    EXPECT_TRUE(cells.locate({120.0f, 1.7f, 120.0f})) << "the middle block's courtyard";
    EXPECT_FALSE(cells.locate({12.0f, 1.7f, 12.0f})) << "inside the first building";
}
