// SPDX-License-Identifier: MIT
// Zhang, Manocha, Hudson and Hoff, "Visibility Culling using Hierarchical
// Occlusion Maps" (SIGGRAPH 1997), as Moeller and Haines, "Occlusion
// Culling Algorithms", section "The HOM Algorithm", describe it.
//   hom  (hierarchical_occlusion_map_culler.cpp) occluders chosen by size
//        and distance from an occluder set (the skins of
//        occluders/skin_occluders.h: large, few polygons, tight
//        boxes, the criteria the chapter gives), a budget of them per
//        frame that may adapt to how much is culled, rendered white on
//        black at the frame's resolution on the CPU
//        (raster/depth_rasterizer.h); occlusion map 0 averages blocks of
//        map-divisor x map-divisor frame pixels, so its opacity is the
//        covered share of each block (hierarchical_occlusion_map.h), its
//        pyramid by averaging; the overlap test with opacity thresholds
//        O_{k+1} = (3 + O_k)/4 (O_0 = 1 - tolerance: the share of a block
//        that may be holes; exact at tolerance 0), then the depth test
//        against the depth estimation buffer, regions holding their
//        occluders' farthest depth (each occluder polygon's farthest
//        vertex, Zhang's estimate).
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily hierarchical_occlusion_map_family();

}  // namespace occu::strategies
