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
#include "traversal/frame_stats.h"
#include "traversal/policies.h"

namespace occu {

struct TraversalOptions {
    // Nodes tested together (in one occlusion pass where the strategy can).
    // 1: strictly front to back, the most culling; more: fewer passes.
    std::size_t batch = 32;
    // Called in this order; they outlive the frame and keep their state
    // across frames.
    std::vector<TraversalPolicy *> policies;
};

// Draws one frame into the current context's bound framebuffer (the caller
// clears it and loads the camera's matrices, gl/state.h) and returns what it
// did: the occluders of the leaves it finds visible as it tests, then the
// see-through triangles of those leaves (SceneRenderer::draw_see_through).
FrameStats render_hierarchy(const SceneRenderer &renderer, const Hierarchy &hierarchy, Culler &culler,
                            const Frame &frame, const TraversalOptions &options = {});

}  // namespace occu
