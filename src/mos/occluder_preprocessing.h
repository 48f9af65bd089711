// Minimum-occluder-set preprocessing for one view (Poon and Wang, section
// 4): which leaves to render as occluders from there, best first.
//   1. An ID buffer of the leaves in the frustum (render/id_buffer.h) at
//      the opacity map's resolution: what is visible, and each leaf's
//      first-hit pixel count.
//   2. Occludees: nodes with more than `min_occludee_triangles` triangles
//      (the paper's 20) none of whose leaves is visible; their screen
//      rectangles as the run-time test sees them.
//   3. Occluder stacks (4.1): occludees in groups of up to 64 with disjoint
//      rectangles; the depth buffer holds each one's nearest depth over its
//      rectangle; for each candidate occluder (a visible leaf of at least
//      `min_occluder_pixels` pixels) one verbose pass of
//      GL_MESAX_occlusion_unit draws it alone, depth tested, with one tile
//      per occludee: the pixel lists are exactly the pixels where it lies in
//      front of each occludee (the paper's depth sorting, per pixel), with
//      no frame read back per occluder.
//   4. Per occludee, the combination table (pixels grouped by the set of
//      occluders covering them) and its cheapest minimum occluder sets
//      (4.2, minimum_occluder_set.h); occludees with an uncovered pixel
//      have none.
//   5. Scores (4.3): gain = occludees the set occludes, plus the gain of
//      every set it is a superset of; cost = occluders + their pixels /
//      `pixels_per_occluder`; score = gain / cost.
//   6. Selection (4.3): sets by score (by default re-scored greedily: gain
//      and cost counting only what the sets chosen before do not already
//      hide and hold), their occluders added in batches;
//      after each batch an ID rendering of the selection keeps only the
//      occluders that show (redundant or hidden ones drop out), until
//      `max_occluders`.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"

namespace occu {

struct PreprocessOptions {
    int resolution = 128;                    // of ID buffers and stacks (the opacity map's)
    std::size_t max_occluders = 256;
    std::uint32_t min_occludee_triangles = 20;
    std::uint32_t min_occluder_pixels = 4;
    std::size_t sets_per_occludee = 4;       // the cheapest MOSs kept per occludee
    std::uint64_t step_budget = 20000;       // MOS search steps per occludee
    // Cost weight of projected size: an occluder costs 1 + pixels / this.
    // The default, a whole 128x128 map, makes the count dominate: with 256
    // MOS took smaller leaves first and needed more of them, and counting
    // occluders measured no slower frames on llvmpipe (README, figure 6).
    double pixels_per_occluder = 16384.0;
    bool marginal_scores = true;             // 6.: greedy by marginal gain / cost; false: the paper's fixed scores
};

struct PreprocessStats {
    std::uint32_t occludees = 0, coverable = 0, candidates = 0, passes = 0, sets = 0;
    std::uint32_t searches_cut = 0;          // occludees whose MOS search hit the budget
};

// Step 6's greedy order (PreprocessOptions::marginal_scores). Section 4.3's
// scores are fixed before selection; once some sets are chosen, a set
// sharing their occluders costs less and one whose occludees they already
// hide gains less. Repeatedly takes the set of highest gain / cost, where
// gain counts occludees not yet hidden (hidden: one of their sets is a
// subset of the occluders chosen so far, the superset rule) that one of
// the set's subsets hides, and cost sums `cost` (by occluder ID; 1 beyond
// it) over occluders not yet chosen: the usual greedy rule for covering
// most with a budget. Sets that add nothing follow in their given order.
// `sets`: sorted ID lists in static score order; `sets_of`: per occludee,
// its minimum occluder sets (sorted). Returns indices into `sets`.
std::vector<std::size_t> order_by_marginal_score(const std::vector<std::vector<std::uint32_t>> &sets,
                                                 const std::vector<std::vector<std::vector<std::uint32_t>>> &sets_of,
                                                 const std::vector<double> &cost);

// Needs a current context with GL_MESAX_occlusion_unit and a framebuffer of
// at least resolution x resolution; clobbers it.
std::vector<std::uint32_t> select_occluders_for_view(const SceneRenderer &renderer, const Hierarchy &hierarchy,
                                                     const Camera &camera, const PreprocessOptions &options,
                                                     PreprocessStats *stats = nullptr);

}  // namespace occu
