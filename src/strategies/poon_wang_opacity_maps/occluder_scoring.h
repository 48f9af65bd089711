// SPDX-License-Identifier: MIT
// Scoring and selecting minimum occluder sets (Poon and Wang, section 4.3).
//   Scores: gain = occludees the set occludes, plus the gain of every set
//   it is a superset of (occluder fusion); cost = the set's occluders, each
//   1 + its pixels / pixels_per_occluder (the paper approximates the
//   run-time cost by the number and projected size of the occluders);
//   score = gain / cost.
//   Order: by score, or (marginal) greedily re-scored as sets are taken.
//   Selection: sets in order, their occluders added in batches; after each
//   batch an ID rendering of the selection keeps only the occluders that
//   show, so redundant or hidden ones drop out, up to `max_occluders`.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.h"
#include "render/id_buffer.h"

namespace occu {

using OccluderSet = std::vector<std::uint32_t>;   // sorted occluder IDs

struct ScoredSets {
    std::vector<OccluderSet> sets;    // distinct sets, by static score, best first
    std::vector<double> scores;
};

// `sets_of`: per coverable occludee, its minimum occluder sets; `cost` by
// occluder ID (1 beyond it).
ScoredSets score_sets(const std::vector<std::vector<OccluderSet>> &sets_of, const std::vector<double> &cost);

// The greedy order: repeatedly the set of highest gain / cost, where gain
// counts occludees not yet hidden (hidden: one of their sets is a subset of
// the occluders chosen so far, the superset rule) that one of the set's
// subsets hides, and cost sums `cost` over occluders not yet chosen: the
// usual greedy rule for covering most within a budget. Sets that add
// nothing follow in their given order. Returns indices into `sets`.
std::vector<std::size_t> order_by_marginal_score(const std::vector<OccluderSet> &sets,
                                                 const std::vector<std::vector<OccluderSet>> &sets_of,
                                                 const std::vector<double> &cost);

// Occluders of `sets` in order, without redundancy (ID rendering of the
// selection at resolution x resolution with `ids`), at most max_occluders.
std::vector<std::uint32_t> select_without_redundancy(IdBuffer &ids, const Camera &camera,
                                                     const std::vector<OccluderSet> &sets, std::size_t nodes,
                                                     int resolution, std::size_t max_occluders);

}  // namespace occu
