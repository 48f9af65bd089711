// SPDX-License-Identifier: MIT
// Leone, Barbagallo, Banquiero, Agromayor and Bursztyn, "Implementing
// Software Occlusion Culling for Real-Time Applications": occlusion
// culling on the CPU against a downscaled depth buffer.
//   occluders=skins  the occluder skins of section 4 (a few boxes inside
//                    each mesh, preprocessed: occluders/occluder_skins.h),
//                    frustum-culled, the largest on screen first, their
//                    faces that face the eye rasterized as quads (section 5);
//   occluders=drawn  the triangles of the leaves already drawn this frame,
//                    front to back, as a z-buffer fills (the way of Intel's
//                    Masked Occlusion Culling), for comparison on the same
//                    frames;
//   occluders=both   the skins first, then the drawn leaves' triangles,
//                    which add what skins lack: the silhouettes they are
//                    shrunk inside of, and details (ledges) too thin for
//                    a voxel.
// A node is tested by its screen rectangle at its nearest depth, with an
// early out at the first depth pixel not nearer (section 6); a leaf that
// fails is tested again by its box's faces that face the eye, pixel by
// pixel at their own nearest depth (occludee=box; occludee=rect is section
// 6 alone): the rectangle's corners outside the box's silhouette and the
// depth of its far parts no longer keep it (98.4% culling efficiency on the
// dense route against 97.8%). The depth
// buffer (raster/depth_rasterizer.h) is conservative by construction at
// any map-divisor, with per-pixel depth or one farthest depth per polygon
// (section 5's "optimal choice").
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily occluder_skins_family();

}  // namespace occu::strategies
