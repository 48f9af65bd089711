// SPDX-License-Identifier: MIT
// Cull maps (Wonka, Wimmer and Schmalstieg 2000, sections 1.3 and 5;
// strategies/wonka_view_cells/cull_map.h) against brute force: the umbra at
// every pixel centre computed on the CPU from the definition (a point is
// hidden from a sample point when the sight line to it passes below the top
// of some occluder wall; the umbra of several sample points is the lowest of
// theirs) equals the GL map up to the depth buffer's precision, away from the
// shadows' side edges, where sampling at pixel centres decides; and the
// read-back and Occlusion Unit object tests agree box for box.
#include "strategies/wonka_view_cells/cull_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gl/offscreen_context.h"

using namespace occu;

namespace {

PrismOccluder rectangle(double x0, double z0, double x1, double z1, double top)
{
    PrismOccluder f;
    f.outline = {{x0, z0}, {x1, z0}, {x1, z1}, {x0, z1}};
    f.top = top;
    return f;
}

PrismOccluder l_shape(double top)
{
    PrismOccluder f;
    f.outline = {{60, 10}, {80, 10}, {80, 18}, {68, 18}, {68, 30}, {60, 30}};
    f.top = top;
    return f;
}

bool inside_outline(const PrismOccluder &o, const glm::dvec2 &p)
{
    bool in = false;
    const auto &poly = o.outline;
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
        if ((poly[i].y > p.y) != (poly[j].y > p.y) &&
            p.x < (poly[j].x - poly[i].x) * (p.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x)
            in = !in;
    return in;
}

struct Umbra {
    double height;
    double edge_distance;   // to the nearest side ray of a shadow wedge, metres
};

// The umbra at q from p: the highest shadow plane among the edges whose
// wedge (beyond the edge, between the rays from p through its ends) holds q.
Umbra umbra_from(const glm::dvec3 &p, const std::vector<PrismOccluder> &occluders, const glm::dvec2 &q, double bottom,
                 double top)
{
    Umbra u{bottom, 1e300};
    const glm::dvec2 eye(p.x, p.z);
    for (const PrismOccluder &o : occluders)
        for (std::size_t i = 0, j = o.outline.size() - 1; i < o.outline.size(); j = i++) {
            const glm::dvec2 a = o.outline[j], b = o.outline[i];
            const glm::dvec2 d = q - eye, ab = b - a;
            // q = eye + t (a + s (b - a) - eye), s in [0, 1], t >= 1.
            const double den = d.x * ab.y - d.y * ab.x;
            if (den == 0.0)
                continue;
            const glm::dvec2 ae = a - eye;
            const double s = (d.x * ae.y - d.y * ae.x) / -den;
            const double r = (ae.x * ab.y - ae.y * ab.x) / den;   // the edge point is eye + r d
            if (s < 0.0 || s > 1.0 || r <= 0.0 || r > 1.0)
                continue;
            const double t = 1.0 / r;   // q's parameter along the ray through the edge point
            u.height = std::max(u.height, std::min(top, p.y + t * (o.top - p.y)));
            // Distance from q to the side rays through a and b.
            for (const glm::dvec2 &e : {a, b}) {
                const glm::dvec2 dir = glm::normalize(e - eye);
                const glm::dvec2 w = q - eye;
                u.edge_distance = std::min(u.edge_distance, std::abs(w.x * dir.y - w.y * dir.x));
            }
            // And to the edge itself.
            const double len2 = glm::dot(ab, ab);
            const double tt = std::clamp(glm::dot(q - a, ab) / len2, 0.0, 1.0);
            u.edge_distance = std::min(u.edge_distance, glm::length(q - (a + tt * ab)));
        }
    return u;
}

}  // namespace

TEST(CullMap, EqualsTheUmbraComputedFromItsDefinition)
{
    gl::OffscreenContext ctx(16, 16);
    const double bottom = -1.0, top = 60.0;
    CullMap map(bottom, top);
    CullMapRegion region;
    region.min = {0.0, 0.0};
    region.width = 100;
    region.height = 80;
    region.pixel = 1.0;
    const std::vector<PrismOccluder> occluders = {rectangle(30, 30, 40, 50, 20), rectangle(50, 40, 54, 44, 8),
                                                  l_shape(30), rectangle(10, 60, 30, 64, 1.5)};
    std::vector<const PrismOccluder *> pointers;
    for (const PrismOccluder &o : occluders)
        pointers.push_back(&o);
    // Then two close to an occluder's corner (0.56 m and 2.76 m off its two
    // faces) and one 1 m in front of the middle of a wall, 5 m from its
    // corners: their wedges must reach across the map all the same.
    const std::vector<glm::dvec3> samples = {{20.5, 2.0, 20.5}, {24.0, 2.0, 18.0}, {18.0, 2.0, 24.0}, {22.0, 10.0, 15.0},
                                             {40.56, 2.0, 27.24}, {40.3, 2.0, 28.0}, {35.0, 2.0, 29.0}};
    map.begin(region);
    for (std::size_t s = 0; s < samples.size(); ++s) {
        map.add_sample_point(samples[s], pointers);
        const std::vector<std::uint32_t> depths = map.read_depths();
        int compared = 0, hidden = 0;
        for (int y = 0; y < region.height; ++y)
            for (int x = 0; x < region.width; ++x) {
                const glm::dvec2 q(x + 0.5, y + 0.5);
                double expected = top;
                double near_edge = 1e300;
                for (std::size_t k = 0; k <= s; ++k) {
                    const Umbra u = umbra_from(samples[k], occluders, q, bottom, top);
                    expected = std::min(expected, u.height);
                    near_edge = std::min(near_edge, u.edge_distance);
                }
                if (near_edge < 0.75)
                    continue;   // the pixel centre near a wedge's side: rasterization decides
                const double got = map.height_of(depths[std::size_t(y) * std::size_t(region.width) + std::size_t(x)]);
                bool in_footprint = false;
                for (const PrismOccluder &o : occluders)
                    in_footprint |= inside_outline(o, q);
                if (in_footprint) {
                    // Inside an occluder seen from above its top only its back
                    // edges are drawn (the map's choice for convex ones): less
                    // occlusion where no object can be, never more.
                    EXPECT_LE(got, expected + 1e-3) << "pixel (" << x << ", " << y << ")";
                    continue;
                }
                ++compared;
                hidden += expected > 0.0;
                EXPECT_NEAR(got, expected, 1e-3) << "pixel (" << x << ", " << y << ") after " << s + 1 << " sample points";
            }
        EXPECT_GT(compared, 5000);
        EXPECT_GT(hidden, 500) << "the occluders hide something";
    }
}

TEST(CullMap, ReadBackAndOcclusionUnitAgreeBoxForBox)
{
    gl::OffscreenContext ctx(16, 16);
    CullMap map(-1.0, 60.0);
    CullMapRegion region;
    region.width = 128;
    region.height = 96;
    region.pixel = 1.0;
    const std::vector<PrismOccluder> occluders = {rectangle(30, 30, 40, 50, 20), l_shape(30)};
    const std::vector<const PrismOccluder *> pointers = {&occluders[0], &occluders[1]};
    map.begin(region);
    map.add_sample_point({20.0, 2.0, 20.0}, pointers);
    map.add_sample_point({22.0, 2.0, 17.0}, pointers);
    const std::vector<std::uint32_t> depths = map.read_depths();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> ux(-10.0f, 140.0f), uz(-10.0f, 110.0f), size(0.2f, 15.0f), height(0.0f, 70.0f);
    std::vector<Aabb> boxes;
    for (int i = 0; i < 400; ++i) {
        const glm::vec3 lo(ux(rng), 0.0f, uz(rng));
        boxes.push_back(Aabb{lo, lo + glm::vec3(size(rng), height(rng), size(rng))});
    }
    gl::OcclusionUnit unit;
    std::size_t passes = 0;
    const std::vector<std::optional<bool>> by_unit = map.visible_by_unit(unit, boxes, &passes);
    int visible = 0, hidden = 0, outside = 0;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const std::optional<bool> read = map.visible_by_readback(boxes[i], depths);
        EXPECT_EQ(read.has_value(), by_unit[i].has_value()) << "box " << i;
        if (read && by_unit[i])
            EXPECT_EQ(*read, *by_unit[i]) << "box " << i;
        visible += read.value_or(false);
        hidden += read.has_value() && !*read;
        outside += !read.has_value();
    }
    EXPECT_GT(visible, 50);
    EXPECT_GT(hidden, 20);
    EXPECT_GT(outside, 5);
    EXPECT_GT(passes, 1u) << "overlapping boxes need passes of their own";
}
