// SPDX-License-Identifier: MIT
// Random occluders, eyes and boxes, and brute-force visibility, for the
// tests of shadow culling's two geometries (Moeller and Haines, "Occlusion
// Culling Algorithms", section "Shadow Culling"): Hudson et al.'s shadow
// frusta (hudson_shadow_frusta/shadow_frusta_test.cpp) and Coorg and
// Teller's supporting planes (coorg_teller_supporting_planes/
// supporting_planes_test.cpp). A point is hidden when the segment from the
// eye to it crosses the occluder (a convex polygon, or a box aggregate).
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/aabb.h"

namespace occu::shadow_samples {

using Random = std::mt19937;

inline double uniform(Random &r, double a, double b) { return std::uniform_real_distribution<double>(a, b)(r); }

inline glm::dvec3 random_point(Random &r, double extent)
{
    return {uniform(r, -extent, extent), uniform(r, -extent, extent), uniform(r, -extent, extent)};
}

inline glm::dvec3 random_unit(Random &r)
{
    for (;;) {
        const glm::dvec3 p = random_point(r, 1.0);
        const double l = glm::length(p);
        if (l > 0.1 && l <= 1.0)
            return p / l;
    }
}

// Float coordinates, as the scene's.
inline glm::dvec3 as_float(const glm::dvec3 &p) { return glm::dvec3(glm::vec3(p)); }

inline Aabb random_box(Random &r, const glm::dvec3 &centre, double max_half)
{
    const glm::dvec3 half{uniform(r, 0.02, max_half), uniform(r, 0.02, max_half), uniform(r, 0.02, max_half)};
    return Aabb::of(glm::vec3(centre - half), glm::vec3(centre + half));
}

// A convex polygon of 3 to 8 vertices on an ellipse in a random plane.
struct Polygon {
    std::vector<glm::dvec3> vertices;
    glm::dvec3 centre, normal, u, v;
};

inline Polygon random_polygon(Random &r)
{
    Polygon p;
    p.centre = random_point(r, 10.0);
    p.normal = random_unit(r);
    p.u = glm::normalize(glm::cross(p.normal, random_unit(r)));
    p.v = glm::cross(p.normal, p.u);
    const double a = uniform(r, 0.5, 6.0), b = uniform(r, 0.5, 6.0);
    const int n = std::uniform_int_distribution<int>(3, 8)(r);
    std::vector<double> angles;
    for (int i = 0; i < n; ++i)
        angles.push_back(uniform(r, 0.0, 6.283185307179586));
    std::sort(angles.begin(), angles.end());
    for (double t : angles)
        p.vertices.push_back(p.centre + a * std::cos(t) * p.u + b * std::sin(t) * p.v);
    if (uniform(r, 0.0, 1.0) < 0.5)
        std::reverse(p.vertices.begin(), p.vertices.end());   // either winding
    return p;
}

// An eye and a box: half of them aimed (the eye in front of the occluder,
// the box behind it, near its axis) so that many are occluded, half
// anywhere.
struct Viewing {
    glm::dvec3 eye;
    Aabb box;
};

inline Viewing aimed_or_random(Random &r, const glm::dvec3 &centre, const glm::dvec3 &normal, const glm::dvec3 &u,
                               const glm::dvec3 &v, double lateral)
{
    Viewing s;
    if (uniform(r, 0.0, 1.0) < 0.5) {
        const double side = uniform(r, 0.0, 1.0) < 0.5 ? 1.0 : -1.0;
        s.eye = as_float(centre + side * uniform(r, 0.3, 25.0) * normal + uniform(r, -lateral, lateral) * u +
                         uniform(r, -lateral, lateral) * v);
        s.box = random_box(r,
                           centre - side * uniform(r, 0.2, 25.0) * normal + uniform(r, -lateral, lateral) * u +
                               uniform(r, -lateral, lateral) * v,
                           uniform(r, 0.05, 2.0));
    } else {
        s.eye = as_float(random_point(r, 25.0));
        s.box = random_box(r, random_point(r, 25.0), uniform(r, 0.05, 3.0));
    }
    return s;
}

// --- brute force ---------------------------------------------------------------------

// The closed segment [e, p] meets the triangle (a, b, c) (Moeller and
// Trumbore's test, no tolerance).
inline bool segment_meets_triangle(const glm::dvec3 &e, const glm::dvec3 &p, const glm::dvec3 &a,
                                   const glm::dvec3 &b, const glm::dvec3 &c)
{
    const glm::dvec3 d = p - e, e1 = b - a, e2 = c - a;
    const glm::dvec3 h = glm::cross(d, e2);
    const double det = glm::dot(e1, h);
    if (det == 0.0)
        return false;   // parallel: grazing counts as not hidden
    const double inv = 1.0 / det;
    const glm::dvec3 s = e - a;
    const double bu = glm::dot(s, h) * inv;
    if (bu < 0.0 || bu > 1.0)
        return false;
    const glm::dvec3 q = glm::cross(s, e1);
    const double bv = glm::dot(d, q) * inv;
    if (bv < 0.0 || bu + bv > 1.0)
        return false;
    const double t = glm::dot(e2, q) * inv;
    return t >= 0.0 && t <= 1.0;
}

// The segment from the eye to p crosses the polygon (a fan of triangles).
inline bool hidden_by_polygon(const glm::dvec3 &eye, const glm::dvec3 &p, const std::vector<glm::dvec3> &polygon)
{
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
        if (segment_meets_triangle(eye, p, polygon[0], polygon[i], polygon[i + 1]))
            return true;
    return false;
}

// The segment from the eye to p meets the closed box (slabs).
inline bool hidden_by_box(const glm::dvec3 &eye, const glm::dvec3 &p, const glm::dvec3 &lo, const glm::dvec3 &hi)
{
    double t0 = 0.0, t1 = 1.0;
    for (int a = 0; a < 3; ++a) {
        const double d = p[a] - eye[a];
        if (d == 0.0) {
            if (eye[a] < lo[a] || eye[a] > hi[a])
                return false;
            continue;
        }
        double ta = (lo[a] - eye[a]) / d, tb = (hi[a] - eye[a]) / d;
        if (ta > tb)
            std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1)
            return false;
    }
    return true;
}

// The box's corners and `extra` random points inside it.
inline std::vector<glm::dvec3> samples(Random &r, const Aabb &box, int extra)
{
    std::vector<glm::dvec3> s;
    for (int i = 0; i < 8; ++i)
        s.push_back(glm::dvec3(box.corner(i)));
    for (int i = 0; i < extra; ++i)
        s.push_back({uniform(r, box.min.x, box.max.x), uniform(r, box.min.y, box.max.y),
                     uniform(r, box.min.z, box.max.z)});
    return s;
}

// Hidden with room to spare: by the polygon shrunk by a millionth towards
// its centre, the eye and the point each a micrometre clear of its plane.
inline bool robustly_hidden_by_polygon(const glm::dvec3 &eye, const glm::dvec3 &p, const Polygon &poly)
{
    std::vector<glm::dvec3> shrunk;
    for (const glm::dvec3 &v : poly.vertices)
        shrunk.push_back(poly.centre + (v - poly.centre) * (1.0 - 1e-6));
    const double he = glm::dot(poly.normal, eye - poly.centre), hp = glm::dot(poly.normal, p - poly.centre);
    return std::fabs(he) > 1e-6 && std::fabs(hp) > 1e-6 && he * hp < 0.0 && hidden_by_polygon(eye, p, shrunk);
}

constexpr int trials = 20000;

}  // namespace occu::shadow_samples
