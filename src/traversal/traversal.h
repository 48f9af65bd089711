// SPDX-License-Identifier: MIT
// Hierarchical rendering driven by a Culler: the general occlusion culling
// algorithm of Moeller and Haines (figure 2) over the hierarchy, front to
// back (Bartz et al. 1998, section 3: test a node's box, draw it if it is a
// visible leaf, else open it), a batch of nodes at a time, with the
// policies of traversal/policies.h where the caller gives them. A culler
// that is also an OwnTraversal (chc) walks the hierarchy in its own way in
// the frames that test in full; this then only draws and counts for it,
// and its batch does not apply. A switched-off frame is view-frustum
// culled here without calling it, and a probe is this traversal's,
// through its Culler::test.
#pragma once

#include <cstdint>
#include <vector>

#include "culling/culler.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"
#include "traversal/clock.h"
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
    // What times FrameStats::setup_ms and test_ms (traversal/clock.h): the
    // wall clock, or the calling thread's CPU time.
    Clock clock = Clock::wall;
};


// What a strategy that walks the hierarchy itself tells the traversal,
// which draws and counts for it.
class FrameSink {
public:
    // Draws leaf `node` now (found visible, or taken as visible untested).
    virtual void draw_leaf(std::uint32_t node) = 0;
    // Draws leaf `node` now under the condition of a test whose answer the
    // strategy has not read (AsyncCuller::draw_if_visible): the GL draws it
    // only if the test found it visible. Counted as drawn (what was issued).
    virtual void draw_leaf_conditionally(std::uint32_t node) = 0;
    // `node`'s subtree is not drawn this frame: `why` is view_culled or occluded.
    virtual void cull(std::uint32_t node, Visibility why) = 0;
    // `count` more nodes had their occlusion tested.
    virtual void tested(std::uint32_t count) = 0;

protected:
    ~FrameSink() = default;
};

// A strategy whose tests run alongside drawing (coherent hierarchical
// culling, Bittner et al. 2004: results read when they are ready, drawing
// going on meanwhile) walks the hierarchy itself, with its own temporal
// coherence. Its culler is also an OwnTraversal: the traversal calls its
// Culler::begin_frame, then traverse, which draws through `sink`.
class OwnTraversal {
public:
    virtual void traverse(FrameSink &sink) = 0;

protected:
    ~OwnTraversal() = default;
};

// `culler`'s own traversal; null when it has none.
OwnTraversal *own_traversal(Culler &culler);
// Whether `culler` orders the frames it tests in full itself.
bool orders_frame(const Culler &culler);

// Draws one frame into the current context's bound framebuffer (the caller
// clears it and loads the camera's matrices, gl/state.h) and returns what it
// did: the occluders of the leaves it finds visible as it tests, then the
// see-through triangles of those leaves (SceneRenderer::draw_see_through).
FrameStats render_hierarchy(const SceneRenderer &renderer, const Hierarchy &hierarchy, Culler &culler,
                            const Frame &frame, const TraversalOptions &options = {});

}  // namespace occu
