// SPDX-License-Identifier: MIT
// Convex regions bounded by half-spaces, and the facts of convex polygons
// and boxes they are built from: the geometry that object-space shadow
// culling's two tests share (Moeller and Haines, "Occlusion Culling
// Algorithms", section "Shadow Culling": Hudson et al.'s shadow frusta,
// strategies/hudson_shadow_frusta/shadow_frusta.h, and Coorg and Teller's
// supporting planes, strategies/coorg_teller_supporting_planes/
// supporting_planes.h). Pure geometry: no GL. All arithmetic is in double;
// the inputs (scene and eye) are floats, so their differences are exact
// and the planes are accurate to rounding. Every test is taken with a
// `margin`, always against the region: a point within it of a plane is
// outside.
#pragma once

#include <array>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/aabb.h"

namespace occu {

// distance(p) = dot(normal, p) + offset, the normal of unit length; the
// inside is distance > margin.
struct HalfSpace {
    glm::dvec3 normal{0.0};
    double offset = 0.0;
    double distance(const glm::dvec3 &p) const { return glm::dot(normal, p) + offset; }
    // The smallest distance of the box's corners (the corner farthest
    // against the normal, as in view-frustum culling).
    double min_distance(const Aabb &box) const;
};

// A convex region bounded by at most 12 half-spaces; `margin` is how far
// inside every one a point must be to count (the tests' epsilon, in
// metres, scaled to the coordinates involved).
struct ConvexRegion {
    std::array<HalfSpace, 12> planes;
    int count = 0;
    double margin = 0.0;

    void add(const HalfSpace &h) { planes[std::size_t(count++)] = h; }
    bool holds(const glm::dvec3 &p) const;
    // Every point of the box (so: every corner), with the margin grown for
    // the box's own coordinates.
    bool holds(const Aabb &box) const;
};

// The margin for geometry whose coordinates reach `magnitude` (the largest
// absolute coordinate): far above double rounding of such coordinates,
// far below anything a float scene can tell apart.
double shadow_margin(double magnitude);

// The largest absolute coordinate.
double magnitude(const glm::dvec3 &p);
double magnitude(const Aabb &box);
double polygon_magnitude(const std::vector<glm::dvec3> &polygon);

// A plane through `point` with the (not yet unit) normal `normal`; empty
// when the normal has no length to speak of.
std::optional<HalfSpace> plane_through(const glm::dvec3 &point, const glm::dvec3 &normal);

// What the shadow and supporting-plane tests need of a polygon: its unit
// normal along the winding (Newell's) and its edges of nonzero length.
struct PolygonFacts {
    glm::dvec3 normal{0.0};
    std::vector<std::pair<glm::dvec3, glm::dvec3>> edges;   // (start, end)
    double margin = 0.0;
};

// Empty unless `polygon` (vertices in order, either winding) is a convex
// polygon with area: at least three edges longer than `margin` (shorter
// ones are taken as repeated vertices), twice its area above 4 margin^2,
// every turn the winding's way (collinear edges allowed).
std::optional<PolygonFacts> polygon_facts(const std::vector<glm::dvec3> &polygon, double margin);

// The extent of the polygon along `n`: [min, max] of dot(n, vertex). A
// polygon made of floats is not exactly planar; taking its farthest
// vertices keeps every statement conservative.
std::pair<double, double> extent_along(const std::vector<glm::dvec3> &polygon, const glm::dvec3 &n);

// The largest dot(n, corner) over the box's corners.
double max_corner_along(const Aabb &box, const glm::dvec3 &n);

// The unit vector of axis 0, 1 or 2.
glm::dvec3 axis_vector(int axis);

// A box's face f (0..5: axis f / 2, the max side when f is odd) as a quad,
// counter-clockwise seen from outside, and its outward normal.
std::vector<glm::dvec3> box_face(const Aabb &box, int face);
glm::dvec3 box_face_normal(int face);

// Which faces of `box` face the eye, two bits per axis (bit 2 * axis: the
// min face, bit 2 * axis + 1: the max face); empty when the eye is inside
// the box or within `margin` of one of its faces' planes (then which faces
// it sees is not certain).
std::optional<unsigned> front_faces(const glm::dvec3 &eye, const Aabb &box, double margin);

}  // namespace occu
