// SPDX-License-Identifier: MIT
// Hudson et al.'s shadow frusta, the geometry (Hudson, Manocha, Cohen,
// Lin, Hoff and Zhang, "Accelerated Occlusion Culling using Shadow
// Frusta", 1997, as Moeller and Haines, "Occlusion Culling Algorithms",
// section "Shadow Culling", describe it). Pure geometry: no GL; the half-
// spaces, margins and box faces are geometry/convex_region.h's.
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
#pragma once

#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/aabb.h"
#include "geometry/convex_region.h"

namespace occu {

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

}  // namespace occu
