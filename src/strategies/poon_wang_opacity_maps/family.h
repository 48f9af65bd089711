// SPDX-License-Identifier: MIT
// Poon and Wang, "Occlusion Culling Using Minimum Occluder Set and Opacity
// Map": occlusion culling with the opacity map and the sparse depth map
// (section 5; opacity_map.h, sparse_depth_map.h), by one of three occluder
// selections (section 6.1):
//   selection=ps    occluders by projected size (selection.h)
//   selection=fh    occluders by first hit (an ID buffer of the frame)
//   selection=mos   occluders from the minimum-occluder-set database of the
//                   nearest grid point and heading (section 4:
//                   view_preprocessing.h and the files it names;
//                   occluder_database.h, made by occu-preprocess)
// and one of two comparisons (figure 8): compare=maps is the overlap test
// on the opacity map, then the sparse depth map (OM + SDM); compare=pixels
// checks coverage and depth pixel by pixel (the paper's PC).
//
// begin_frame renders the chosen occluders' depth at full resolution into
// the strategy's own framebuffer, reads it back and reduces it by
// map-divisor in each direction to the maps' resolution (128 x 128 for a
// 512 x 512 frame): a map pixel is covered only if all its frame pixels
// are, and its depth is the farthest of them, so every test stays
// conservative. A test takes the box's footprint in map pixels: the
// three-operation overlap test (section 5.2, with `tolerance` hole pixels
// for the approximate test), then the sparse depth comparison with the
// box's nearest depth (sections 5.3 and 5.4). The adaptive overlap test
// (section 5.2): a box its occluders cover less than coverage-ratio of is
// visible, and its descendants go untested.
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily opacity_map_family();

}  // namespace occu::strategies
