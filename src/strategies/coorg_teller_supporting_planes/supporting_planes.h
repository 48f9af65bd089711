// SPDX-License-Identifier: MIT
// Coorg and Teller's supporting planes, the geometry (Coorg and Teller,
// "Real-Time Occlusion Culling for Models with Large Occluders", 1997, as
// Moeller and Haines, "Occlusion Culling Algorithms", section "Shadow
// Culling", describe it). Pure geometry: no GL; the half-spaces, margins
// and box faces are geometry/convex_region.h's.
//
// The chapter: "A supporting plane is constructed [from an edge of the
// occluder and a vertex of the box] ... such that the occluder and the BB
// [are] located on the same side of the plane. An object is occluded if
// the viewer is inside all of the supporting planes". The two functions
// below compute, per occluder edge (per silhouette edge of an aggregate),
// the plane through the edge and the box vertex that has the occluder and
// the box on one side, independent of the eye; testing a viewer is then a
// few dot products. The occluder's plane (the front-face planes of an
// aggregate) is not a supporting plane in this sense but must separate
// viewer and box: it is one more half-space for the viewer, and the box
// must lie strictly behind it, or there are no planes at all.
//
// Equivalence (per edge, in the plane across the edge): with the viewer in
// front of the occluder's plane and the box behind it, the box lies on the
// occluder's side of the plane through E and the edge iff E lies on the
// occluder's side of the supporting plane through that edge (both say that
// the viewer's line through the edge leaves the occluder and the box on
// one side). So the viewer is inside all the supporting planes iff the box
// is inside the shadow frustum, for a polygon and for a box aggregate (the
// silhouette edge's back face then plays the part of the tangent when the
// box does not reach past it; the frusta: strategies/hudson_shadow_frusta/
// shadow_frusta.h). tests/unit/strategies/coorg_teller_supporting_planes/
// supporting_planes_test.cpp checks this numerically against the shadow
// frusta, and both against brute force.
#pragma once

#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/aabb.h"
#include "geometry/convex_region.h"

namespace occu {

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
