// Hierarchical rendering driven by a Culler: the general occlusion culling
// algorithm of Moeller and Haines (figure 2) over the hierarchy, front to
// back (Bartz et al. 1998, section 3: test a node's box, draw it if it is a
// visible leaf, else open it), a batch of nodes at a time, with the
// policies of traversal/policies.h where the caller gives them. A culler
// that orders the frame itself (Culler::orders_frame: chc) walks the
// hierarchy in its own way; this then only draws and counts for it, and
// its batch and temporal coherence do not apply; switch-off does (a
// switched-off frame is view-frustum culled here without calling it; a
// probe is a whole frame of its own traversal).
#pragma once

#include <cstdint>
#include <vector>

#include "culling/culler.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"
#include "traversal/policies.h"

namespace occu {

struct TraversalOptions {
    // Nodes tested together (in one occlusion pass where the strategy can).
    // 1: strictly front to back, the most culling; more: fewer passes.
    std::size_t batch = 32;
    VisibleNodeList *coherence = nullptr;   // temporal coherence, if any
    SwitchOff *switch_off = nullptr;        // adaptive switch-off, if any
};

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
    std::uint64_t triangles_occluded = 0;
    bool occlusion_tested = true;           // false while switched off
    // Wall time in the culler, apart from what it saves: begin_frame
    // (occluders, maps: setup_ms) and the tests (test_ms), including waits
    // for the rasterizer they cause (an occlusion pass waits for the leaves
    // drawn before it); the rest of the frame is drawing.
    double setup_ms = 0.0, test_ms = 0.0;
    std::vector<std::uint32_t> drawn;   // leaf node indices, in drawing order
};

// Draws one frame into the current context's bound framebuffer (the caller
// clears it and loads the camera's matrices, gl/state.h) and returns what it
// did: the occluders of the leaves it finds visible as it tests, then the
// see-through triangles of those leaves (SceneRenderer::draw_see_through).
FrameStats render_hierarchy(const SceneRenderer &renderer, const Hierarchy &hierarchy, Culler &culler,
                            const Frame &frame, const TraversalOptions &options = {});

}  // namespace occu
