// Hierarchical rendering driven by a Culler: the general occlusion culling
// algorithm of Moeller and Haines (figure 2) over the hierarchy, front to
// back (Bartz et al. 1998, section 3: test a node's box, draw it if it is a
// visible leaf, else recurse), a batch of nodes at a time.
#pragma once

#include <cstdint>

#include "camera/camera.h"
#include "culling/culler.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"

namespace occu {

struct TraversalOptions {
    // Nodes tested together (in one occlusion pass where the strategy can).
    // 1: strictly front to back, the most culling; more: fewer passes.
    std::size_t batch = 32;
};

// Temporal coherence (Greene et al.'s visible node list, as in Moeller and
// Haines): nodes that were visible in the previous frame are taken as
// visible again without an occlusion test, except every `retest_period`
// frames (staggered by node), so that nodes which became hidden are found.
// Drawing a node that is hidden is only wasted work, never a wrong pixel,
// so this keeps a conservative strategy conservative, and it removes the
// test cost where the scene has little occlusion. One per strategy and
// hierarchy, kept across frames.
//
// Adaptive switch-off (Bartz et al. 1998, section 5; Poon and Wang lost 30%
// on their open route without one): when occlusion tests culled fewer than
// `switch_off_fraction` of the triangles drawn in a frame, the next frames
// test no occlusion (view-frustum culling only) except probe frames, whose
// result can switch the tests back on. The first probe comes
// `probe_period` frames after switching off; each probe that finds the
// tests still not worth it doubles the wait, up to `max_probe_period`
// (a probe tests everything and costs several frames' worth where there
// is little occlusion, so a long stretch of open views probes rarely).
struct Coherence {
    std::vector<std::uint8_t> visible_last_frame;   // by node
    std::uint32_t frame = 0;
    std::uint32_t retest_period = 8;
    float switch_off_fraction = 0.0f;   // 0: never switch off
    std::uint32_t probe_period = 8;
    std::uint32_t max_probe_period = 64;
    // A probe frame stops testing after this many occlusion passes (the
    // rest of its nodes are taken as visible) and judges by what it saw
    // until then: an unbounded probe of an open view costs several frames
    // (200 passes on the open route), a dense view needs fewer (15 to 60).
    std::uint32_t probe_pass_budget = 64;
    bool occlusion_off = false;
    std::uint32_t probe_wait = 0;        // frames between probes now
    std::uint32_t frames_to_probe = 0;   // until the next probe
};

struct FrameStats {
    std::uint64_t triangles = 0;
    std::uint32_t leaves_drawn = 0;
    std::uint32_t nodes_tested = 0;
    std::uint32_t nodes_view_culled = 0;
    std::uint32_t nodes_occluded = 0;
    std::uint32_t passes = 0;
    std::uint64_t triangles_occluded = 0;   // in the subtrees of nodes found occluded
    bool occlusion_tested = true;           // false while switched off
    // Wall time in the culler, apart from what it saves: begin_frame
    // (occluders, maps: setup_ms) and the tests (test_ms), including waits
    // for the rasterizer they cause (an occlusion pass waits for the leaves
    // drawn before it); the rest of the frame is drawing.
    double setup_ms = 0.0, test_ms = 0.0;
    std::vector<std::uint32_t> drawn;   // leaf node indices, in drawing order
};

// Draws one frame into the current context's bound framebuffer (the caller
// clears it and sets the camera's matrices) and returns what it did.
// With `coherence`, uses and updates it (see Coherence).
FrameStats render_hierarchy(const SceneRenderer &renderer, const Hierarchy &hierarchy, Culler &culler,
                            const Camera &camera, const TraversalOptions &options, Coherence *coherence = nullptr);

// Loads the camera's projection and view into GL's fixed-function matrices.
void load_camera(const Camera &camera);

}  // namespace occu
