// SPDX-License-Identifier: MIT
// Minimum-occluder-set preprocessing for one view (Poon and Wang, section
// 4): which leaves to render as occluders from there, best first. The
// steps, each in the file of its section:
//   4.1  occluder stacks of the view's occludees (occluder_stacks.h);
//   4.2  per occludee, its combination table and cheapest minimum occluder
//        sets (minimum_occluder_set.h); occludees with an uncovered pixel
//        have none;
//   4.3  scores, the greedy order, and selection without redundancy by ID
//        rendering (occluder_scoring.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "geometry/aabb.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"
#include "strategies/poon_wang_opacity_maps/occluder_database.h"
#include "strategies/poon_wang_opacity_maps/occluder_stacks.h"

namespace occu {

struct PreprocessOptions {
    StackOptions stacks;                     // resolution, map divisor, occludee and occluder filters
    std::size_t max_occluders = 256;
    std::size_t sets_per_occludee = 4;       // the cheapest MOSs kept per occludee
    std::uint64_t step_budget = 20000;       // MOS search steps per occludee
    // Cost weight of projected size: an occluder costs 1 + pixels / this.
    // The default, a whole 128x128 map, makes the count dominate: with 256
    // MOS took smaller leaves first and needed more of them, and counting
    // occluders measured no slower frames on llvmpipe
    // (docs/minimum-occluder-sets.md, figure 6).
    double pixels_per_occluder = 16384.0;
    bool marginal_scores = true;             // greedy by marginal gain / cost; false: the paper's fixed scores

    // Every option as "key=value ...", in a fixed order: what a database
    // records of how it was made.
    std::string describe() const;
};

struct PreprocessStats {
    std::uint32_t occludees = 0, coverable = 0, candidates = 0, passes = 0, sets = 0;
    std::uint32_t searches_cut = 0;          // occludees whose MOS search hit the budget
};

// Needs a current context with GL_MESAX_occlusion_unit; draws into
// framebuffers of its own.
std::vector<std::uint32_t> select_occluders_for_view(const SceneRenderer &renderer, const Hierarchy &hierarchy,
                                                     const Camera &camera, const PreprocessOptions &options,
                                                     PreprocessStats *stats = nullptr);

// A database to be made here, its views still to select: its provenance
// (this program's code and Mesa; its settings `options`' with the grid and
// the lens of the views), its grid and its maps' resolution.
OccluderDatabase occluder_database_for(const Hierarchy &hierarchy, const OccluderGrid &grid, const Camera &lens,
                                       const PreprocessOptions &options);

// A whole database made here, for the grid's every view with the lens
// `lens`, selected by select_occluders_for_view with `options`
// (options.stacks.resolution: the run-time maps' resolution). Needs what
// select_occluders_for_view needs.
OccluderDatabase preprocess_database(const SceneRenderer &renderer, const Hierarchy &hierarchy, const OccluderGrid &grid,
                                     const Camera &lens, const PreprocessOptions &options);

}  // namespace occu
