// SPDX-License-Identifier: MIT
// Minimum occluder sets (Poon and Wang, section 4.2). An occludee's
// combination table lists, for each group of its pixels, the occluders that
// cover that group (a slot); the slots are sorted by how many occluders they
// hold. A set of occluders that includes at least one occluder of every slot
// covers the occludee; a minimum occluder set (MOS) is such a set none of
// whose members can be left out.
//
// The search is the paper's: left to right, take the first slot not yet
// cancelled, try each of its occluders in turn (cancelling every slot that
// occluder covers), and backtrack. Every MOS is found this way (each step
// can pick a member of it); sets the search produces that are not minimal
// are dropped. Cost pruning (the paper's "backtrack immediately" when the
// intermediate set already costs more than those kept) and a budget on the
// steps bound the O(n!) worst case.
#pragma once

#include <cstdint>
#include <vector>

namespace occu {

using OccluderId = std::uint32_t;

struct MosSearchOptions {
    // Per-occluder cost (indexed by id); missing ids cost 1. The paper
    // approximates it by the occluder count and projected size.
    std::vector<double> cost;
    // Keep only the cheapest sets (0: all); enables cost pruning.
    std::size_t keep_cheapest = 0;
    // Search steps (occluder picks) before giving up; 0: unbounded.
    std::uint64_t step_budget = 0;
};

struct MosSearchResult {
    std::vector<std::vector<OccluderId>> sets;   // each sorted; sorted by cost, then lexicographically
    bool complete = true;                        // false when the budget ran out
    std::uint64_t steps = 0;
};

// `slots`: the combination table, each slot the occluders covering one group
// of pixels. An empty slot (pixels no occluder covers) means the occludee
// cannot be covered: no sets.
MosSearchResult minimum_occluder_sets(const std::vector<std::vector<OccluderId>> &slots,
                                      const MosSearchOptions &options = {});

}  // namespace occu

namespace occu {

// The combination table of an occludee (section 4.2) from its occluder
// stack (one occluder list per pixel): the distinct lists, sorted, fewest
// occluders first. Empty when a pixel has no occluder (the occludee is
// visible and has no MOS). The stack's lists are consumed.
std::vector<std::vector<OccluderId>> combination_table(std::vector<std::vector<OccluderId>> &stack);

}  // namespace occu
