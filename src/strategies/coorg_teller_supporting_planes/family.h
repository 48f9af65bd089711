// SPDX-License-Identifier: MIT
// Coorg and Teller, "Real-Time Occlusion Culling for Models with Large
// Occluders" (Symposium on Interactive 3D Graphics 1997), as Moeller and
// Haines, "Occlusion Culling Algorithms", section "Shadow Culling",
// describe it.
//   planes  (supporting_plane_culler.cpp) the occluders of shadow
//           (occluders/shadow_occluders.h); a node is
//           culled when the viewer is inside all the supporting planes of
//           an occluder and the node's box (each through an occluder edge,
//           or silhouette edge of an aggregate, and a box vertex, occluder
//           and box on one side), and in front of the occluder's plane with
//           the box behind it (supporting_planes.h). The planes of a pair
//           do not depend on the eye, so they are made at the pair's first
//           test and kept across frames (plane-cache; an aggregate's per
//           region of viewpoints, as its silhouette changes); a frame tests
//           the eye alone. For a single convex occluder the answer equals
//           shadow's (supporting_planes.h shows why;
//           tests/unit/strategies/coorg_teller_supporting_planes/
//           supporting_planes_test.cpp checks it).
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily supporting_plane_family();

}  // namespace occu::strategies
