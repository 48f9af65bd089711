// Object-space shadow culling, the geometry (Moeller and Haines, "Occlusion
// Culling Algorithms", section "Shadow Culling": Hudson et al.'s shadow
// frusta and Coorg and Teller's supporting planes). Pure geometry: no GL.
// All arithmetic is in double; the inputs (scene and eye) are floats, so
// their differences are exact and the planes are accurate to rounding.
//
// Shadows. For an occluder X and a point eye E, a point P is hidden when
// the segment EP meets X. For a convex X the hidden points form a convex
// set: if EP1 meets X at c1 and EP2 at c2, the segment c1c2 lies in X and
// crosses the triangle E P1 P2 from side EP1 to side EP2, so it separates
// E from every point of P1P2. A box therefore lies in the shadow iff its
// eight corners do, and the tests below are exact (up to `margin`, always
// taken against occlusion).
//
// Hudson et al. (the chapter: "the frustum does not have a far plane and
// may have more than four side planes ... The near plane is the plane in
// which the occluder lies"): for a convex polygon the shadow is the cone
// from E over the polygon (one side plane through E and each edge) cut by
// the polygon's plane (polygon_shadow).
//
// Aggregates (Coorg and Teller: "several polygons that share edges as an
// aggregate occluder"): the faces of a box that face E, the box's near
// surface. For a convex polyhedron C (box_shadow) the shadow is exactly
//   the cone from E over C: side planes through E and C's silhouette edges
//     (the edges between a face E sees and one it does not: 4 or 6 of a
//     box's 12), together with
//   the far side of every plane of a face that faces E (1, 2 or 3 planes).
// Proof. A ray from E that meets C enters it at t_in = the largest of its
// crossings t_k of the planes of the front faces (outside such a plane E
// must cross it to get in; the back faces' planes only bound the exit,
// Cyrus and Beck's clipping). So a point of the ray is hidden iff it lies
// at or beyond t_in, iff it is beyond every front-face plane. The cone's
// side planes say the ray meets C at all. Both conditions are necessary
// and together sufficient, so a box is in the shadow iff its corners
// satisfy all of them; the box's shadow holds the shadows of its front
// faces and the boxes that straddle two of them.
//
// Coorg and Teller (the chapter: "A supporting plane is constructed [from
// an edge of the occluder and a vertex of the box] ... such that the
// occluder and the BB [are] located on the same side of the plane. An
// object is occluded if the viewer is inside all of the supporting
// planes"): supporting_planes computes, per occluder edge (per silhouette
// edge of an aggregate), the plane through the edge and the box vertex
// that has the occluder and the box on one side, independent of the eye;
// testing a viewer is then a few dot products. The occluder's plane (the
// front-face planes of an aggregate) is not a supporting plane in this
// sense but must separate viewer and box: it is one more half-space for
// the viewer, and the box must lie strictly behind it, or there are no
// planes at all.
//
// Equivalence (per edge, in the plane across the edge): with the viewer in
// front of the occluder's plane and the box behind it, the box lies on the
// occluder's side of the plane through E and the edge iff E lies on the
// occluder's side of the supporting plane through that edge (both say that
// the viewer's line through the edge leaves the occluder and the box on
// one side). So the viewer is inside all the supporting planes iff the box
// is inside the shadow frustum, for a polygon and for a box aggregate (the
// silhouette edge's back face then plays the part of the tangent when the
// box does not reach past it). tests/unit/occluders/shadow_volumes_test.cpp
// checks this numerically against the shadow frusta and both against
// brute force.
#pragma once

#include <array>
#include <optional>
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

// --- Hudson et al.: shadow frusta -------------------------------------------------

// The shadow volume of the convex polygon `polygon` (vertices in order,
// either winding) seen from `eye`: side planes through the eye and each
// edge, the near plane the polygon's own (inside = beyond it). Empty when
// the polygon has fewer than three edges of nonzero length, no area, is
// not convex, or the eye lies within the margin of its plane.
std::optional<ConvexRegion> polygon_shadow(const glm::dvec3 &eye, const std::vector<glm::dvec3> &polygon);

// The shadow of the box `occluder` (Coorg and Teller's aggregate of its
// faces that face the eye): silhouette side planes and the front faces'
// planes (above). Empty when the box is degenerate (an extent of zero) or
// the eye lies inside it or within the margin of one of its faces' planes.
std::optional<ConvexRegion> box_shadow(const glm::dvec3 &eye, const Aabb &occluder);

// A box's face f (0..5: axis f / 2, the max side when f is odd) as a quad,
// counter-clockwise seen from outside, and its outward normal.
std::vector<glm::dvec3> box_face(const Aabb &box, int face);
glm::dvec3 box_face_normal(int face);

// Which faces of `box` face the eye, two bits per axis (bit 2 * axis: the
// min face, bit 2 * axis + 1: the max face); empty when the eye is inside
// the box or within `margin` of one of its faces' planes (then which faces
// it sees is not certain).
std::optional<unsigned> front_faces(const glm::dvec3 &eye, const Aabb &box, double margin);

// --- Coorg and Teller: supporting planes ----------------------------------------------

// The half-spaces a viewer must be inside for `box` to be hidden by the
// convex polygon: the polygon's plane, on the side away from the box, and
// one supporting plane per edge. Empty when the box is not strictly on one
// side of the polygon's plane (then no viewer sees it hidden), or the
// polygon is degenerate as for polygon_shadow.
std::optional<ConvexRegion> polygon_supporting_planes(const std::vector<glm::dvec3> &polygon, const Aabb &box);

// The same for the box aggregate `occluder` seen from the region of
// viewers that see its faces `front` (front_faces): the region's own
// bounds (in front of every front face, between the planes of the axes it
// sees no face of) and one supporting plane per silhouette edge. Empty when
// `box` is not strictly behind every front face (or `front` sees no face,
// or both faces of an axis).
std::optional<ConvexRegion> box_supporting_planes(const Aabb &occluder, unsigned front, const Aabb &box);

}  // namespace occu
