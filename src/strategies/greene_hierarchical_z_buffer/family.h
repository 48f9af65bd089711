// SPDX-License-Identifier: MIT
// Greene, Kass and Miller, "Hierarchical Z-Buffer Visibility" (SIGGRAPH
// 1993), as Moeller and Haines, "Occlusion Culling Algorithms", section
// "Hierarchical Z-Buffering and the Hierarchical Visibility Algorithm",
// describe it: a Z-pyramid (z_pyramid.h), each level the farthest of 2x2
// below, against which boxes are tested hierarchically.
//   hzb  (hierarchical_z_buffer_culler.cpp) the pyramid built per frame
//        from the occluder skins' CPU depth buffer (raster/depth_rasterizer.h;
//        Leone et al.'s occluders, occluders/skin_occluders.h) or,
//        source=last-frame, from the depth of the leaves the last frame
//        drew, rendered in this frame's view and read back (the two-pass
//        scheme of GPU culling). Boxes, front to back, are tested from the
//        coarsest level that encloses their footprint in 2x2 texels,
//        descending only where a texel is not nearer than the box; with
//        skins, a leaf the pyramid keeps is tested again by its box's faces
//        in the skins' depth buffer, pixel by pixel, as skins does.
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily hierarchical_z_buffer_family();

}  // namespace occu::strategies
