// SPDX-License-Identifier: MIT
// Hudson, Manocha, Cohen, Lin, Hoff and Zhang, "Accelerated Occlusion
// Culling using Shadow Frusta" (Symposium on Computational Geometry 1997),
// as Moeller and Haines, "Occlusion Culling Algorithms", section "Shadow
// Culling", describe it.
//   shadow  (shadow_frustum_culler.cpp) a few large occluders per frame,
//           chosen by Coorg and Teller's solid-angle estimate
//           g = -a (n . v) / (d . d) with last frame's kept unless one
//           twice as good appears (occluders/shadow_occluders.h): the faces of the
//           occluder skins (occluders/skin_occluders.h) that face
//           the eye, or (aggregate=on, the default) each skin box whole,
//           its front faces one aggregate occluder. Each casts a shadow
//           frustum from the eye, without a far plane: side planes through
//           the eye and the occluder's edges (its silhouette's, for a box),
//           the occluder's plane as near plane (its front faces' planes,
//           for a box); a node whose box lies wholly inside one is culled,
//           tested against the occluder that culled it last first. Exact
//           for convex occluders, with a margin against occlusion
//           (shadow_frusta.h); skins whose mesh the eye may be inside, or
//           whose mesh's surface the near plane may clip, are not used.
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily shadow_frustum_family();

}  // namespace occu::strategies
