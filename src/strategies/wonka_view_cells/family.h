// SPDX-License-Identifier: MIT
// Wonka, Wimmer and Schmalstieg, "Visibility Preprocessing with Occluder
// Fusion for Urban Walkthroughs" (2000): view cells over the city's
// streets, each with its potentially visible set precomputed from point
// samples of its boundary against occluders shrunk by epsilon, fused in
// cull maps (sections 2-6; view_cell_visibility.h).
//   pvs   looks up the view cell that holds the eye (section 3) and draws
//         its set cut by the view frustum (section 7.3): no per-frame
//         occlusion work at all. Conservative for every eye in the cell.
//         The sets come from a database (pvs-database=FILE, made by
//         occu-preprocess view-cells; its provenance must match the
//         hierarchy); without one each cell's set is made the first time
//         the eye enters it. An eye in no cell (inside a building, within
//         the cells' clearance of one, above the cells' tops), or a near
//         plane that reaches farther than that clearance, is drawn with
//         view-frustum culling, and the run's summary says in how many frames.
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily view_cell_family();

}  // namespace occu::strategies
