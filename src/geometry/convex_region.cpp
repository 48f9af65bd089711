// SPDX-License-Identifier: MIT
#include "geometry/convex_region.h"

#include <algorithm>
#include <cmath>

namespace occu {

namespace {

glm::dvec3 lo(const Aabb &b) { return glm::dvec3(b.min); }
glm::dvec3 hi(const Aabb &b) { return glm::dvec3(b.max); }

double min_corner_along(const Aabb &box, const glm::dvec3 &n) { return -max_corner_along(box, -n); }

}  // namespace

glm::dvec3 axis_vector(int axis)
{
    glm::dvec3 v(0.0);
    v[axis] = 1.0;
    return v;
}

std::optional<HalfSpace> plane_through(const glm::dvec3 &point, const glm::dvec3 &normal)
{
    const double length = glm::length(normal);
    if (!(length > 0.0) || !std::isfinite(length))
        return std::nullopt;
    const glm::dvec3 n = normal / length;
    return HalfSpace{n, -glm::dot(n, point)};
}

std::optional<PolygonFacts> polygon_facts(const std::vector<glm::dvec3> &polygon, double margin)
{
    const std::size_t n = polygon.size();
    if (n < 3)
        return std::nullopt;
    PolygonFacts f;
    f.margin = margin;
    glm::dvec3 newell(0.0);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 &a = polygon[i], &b = polygon[(i + 1) % n];
        newell += glm::cross(a, b);
        // Edges no longer than the margin are taken as repeated vertices:
        // their neighbours bound the same shadow.
        if (glm::length(b - a) > margin)
            f.edges.emplace_back(a, b);
    }
    // Twice the area: a sliver is no occluder (its side planes would be
    // unreliable, and it hides nothing).
    const double twice_area = glm::length(newell);
    if (f.edges.size() < 3 || !(twice_area > margin * margin * 4.0) || !std::isfinite(twice_area))
        return std::nullopt;
    f.normal = newell / twice_area;
    // Convex: every turn from one edge to the next goes the winding's way
    // (collinear edges allowed, with a tolerance relative to the edges).
    for (std::size_t i = 0; i < f.edges.size(); ++i) {
        const glm::dvec3 e0 = f.edges[i].second - f.edges[i].first;
        const glm::dvec3 e1 = f.edges[(i + 1) % f.edges.size()].second - f.edges[(i + 1) % f.edges.size()].first;
        if (glm::dot(glm::cross(e0, e1), f.normal) < -1e-12 * glm::length(e0) * glm::length(e1))
            return std::nullopt;
    }
    return f;
}

std::pair<double, double> extent_along(const std::vector<glm::dvec3> &polygon, const glm::dvec3 &n)
{
    double a = glm::dot(n, polygon[0]), b = a;
    for (const glm::dvec3 &v : polygon) {
        a = std::min(a, glm::dot(n, v));
        b = std::max(b, glm::dot(n, v));
    }
    return {a, b};
}

double polygon_magnitude(const std::vector<glm::dvec3> &polygon)
{
    double m = 0.0;
    for (const glm::dvec3 &v : polygon)
        m = std::max(m, magnitude(v));
    return m;
}

double max_corner_along(const Aabb &box, const glm::dvec3 &n)
{
    const glm::dvec3 c{n.x >= 0 ? box.max.x : box.min.x, n.y >= 0 ? box.max.y : box.min.y,
                       n.z >= 0 ? box.max.z : box.min.z};
    return glm::dot(n, c);
}

double HalfSpace::min_distance(const Aabb &box) const { return min_corner_along(box, normal) + offset; }

bool ConvexRegion::holds(const glm::dvec3 &p) const
{
    const double m = std::max(margin, shadow_margin(magnitude(p)));
    for (int i = 0; i < count; ++i)
        if (!(planes[std::size_t(i)].distance(p) > m))
            return false;
    return true;
}

bool ConvexRegion::holds(const Aabb &box) const
{
    if (box.empty())
        return false;
    const double m = std::max(margin, shadow_margin(magnitude(box)));
    for (int i = 0; i < count; ++i)
        if (!(planes[std::size_t(i)].min_distance(box) > m))
            return false;
    return count > 0;
}

double shadow_margin(double magnitude) { return 1e-9 * (1.0 + magnitude); }

double magnitude(const glm::dvec3 &p) { return std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}); }

double magnitude(const Aabb &box) { return std::max(magnitude(lo(box)), magnitude(hi(box))); }

std::vector<glm::dvec3> box_face(const Aabb &box, int face)
{
    const int a = face / 2, u = (a + 1) % 3, v = (a + 2) % 3;
    const bool max_side = face % 2 == 1;
    glm::dvec3 p(0.0);
    p[a] = max_side ? double(box.max[a]) : double(box.min[a]);
    auto at = [&](bool hu, bool hv) {
        glm::dvec3 q = p;
        q[u] = hu ? double(box.max[u]) : double(box.min[u]);
        q[v] = hv ? double(box.max[v]) : double(box.min[v]);
        return q;
    };
    // e_u x e_v = e_a: (u, v) counter-clockwise is counter-clockwise seen
    // from +a, the max face's outside; the min face goes the other way.
    if (max_side)
        return {at(false, false), at(true, false), at(true, true), at(false, true)};
    return {at(false, false), at(false, true), at(true, true), at(true, false)};
}

glm::dvec3 box_face_normal(int face) { return (face % 2 ? 1.0 : -1.0) * axis_vector(face / 2); }

std::optional<unsigned> front_faces(const glm::dvec3 &eye, const Aabb &box, double margin)
{
    unsigned mask = 0;
    for (int a = 0; a < 3; ++a) {
        const double l = box.min[a], h = box.max[a], e = eye[a];
        if (e < l - margin)
            mask |= 1u << (2 * a);
        else if (e > h + margin)
            mask |= 1u << (2 * a + 1);
        else if (!(e > l + margin && e < h - margin))
            return std::nullopt;   // within the margin of a face's plane (or a degenerate axis)
    }
    if (mask == 0)
        return std::nullopt;       // the eye is inside
    return mask;
}

}  // namespace occu
