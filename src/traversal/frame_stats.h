// SPDX-License-Identifier: MIT
// What the traversal did in one frame (traversal/traversal.h), which its
// policies (traversal/policies.h) judge by.
#pragma once

#include <cstdint>
#include <vector>

namespace occu {

struct FrameStats {
    std::uint64_t triangles = 0;
    std::uint32_t leaves_drawn = 0;
    // Of leaves_drawn, those issued under conditional rendering on a tile
    // (FrameSink::draw_leaf_conditionally): the GL drew only those its test
    // found visible. They count as drawn here and in `drawn`.
    std::uint32_t leaves_conditional = 0;
    std::uint32_t nodes_tested = 0;
    std::uint32_t nodes_view_culled = 0;
    std::uint32_t nodes_occluded = 0;
    std::uint32_t passes = 0;               // the culler's report
    // In the subtrees of nodes found occluded, less the leaves wholly outside
    // the frustum (view-frustum culling would not have drawn them either):
    // what the occlusion tests saved, which the switch-off judges by.
    // Counted only where a policy reads it
    // (TraversalPolicy::reads_triangles_occluded); 0 elsewhere.
    std::uint64_t triangles_occluded = 0;
    bool occlusion_tested = true;           // false while switched off
    // Time in the culler, apart from what it saves: begin_frame
    // (occluders, maps: setup_ms) and the tests (test_ms); the rest of the
    // frame is drawing. On the wall clock (TraversalOptions::clock) this
    // includes the waits for the rasterizer they cause (an occlusion pass
    // waits for the leaves drawn before it); on the thread clock it is the
    // calling thread's CPU time alone, without those waits nor llvmpipe's
    // own threads' work (traversal/clock.h).
    double setup_ms = 0.0, test_ms = 0.0;
    std::vector<std::uint32_t> drawn;   // leaf node indices, in drawing order
};

}  // namespace occu
