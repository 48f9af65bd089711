// SPDX-License-Identifier: MIT
// The interface every culling strategy implements (in the manner of Intel's
// Masked Occlusion Culling: clear and render occluders, then test boxes).
//
// Conventions, for every strategy and every caller:
//   world      right-handed, y up, metres (geometry/aabb.h);
//   camera     OpenGL's: looks down its -z axis, clip z in [-w, w], window
//              depth in [0, 1], 0 nearest (camera/camera.h);
//   screen     window pixels of the frame's viewport, (0, 0) its lower left
//              pixel; a box covers its footprint (camera/footprint.h), the
//              one box-to-rectangle rule of the library; a box without one
//              (it holds the eye or crosses the near plane) is visible;
//   hierarchy  nodes are indices into the Hierarchy the strategy was made
//              for (StrategyContext), given once, never per call.
//
// A frame: begin_frame(frame) clears the strategy's occlusion state and
// renders its occluders (into its own framebuffer or memory, never the
// caller's); test() answers for a batch of nodes, front to back; rendered()
// says which leaves the caller drew. Results:
//   visible      the node may contribute pixels: draw it, or open it;
//   occluded     nothing in it can be seen (conservative strategies) or it
//                contributes too little (approximate ones);
//   view_culled  it lies outside the view frustum.
// With visible, `test_below` false is a hint that the node's descendants
// are not worth an occlusion test (Poon and Wang's adaptive overlap test,
// section 5.2): the traversal draws them with frustum culling only.
// Statistics (passes) are reported, never used to steer the traversal.
// Tests answered later, while drawing goes on, are another interface
// (culling/async_culler.h), which a strategy's own traversal drives.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "camera/footprint.h"
#include "geometry/aabb.h"

namespace occu {

enum class Visibility { visible, occluded, view_culled };

const char *visibility_name(Visibility v);

struct VisibilityTruth;
struct NodeTest;

// What a strategy knows of the frame it culls.
struct Frame {
    Frame(const Camera &camera, int viewport_width, int viewport_height, const VisibilityTruth *truth = nullptr);

    Camera camera;
    glm::mat4 view_projection;
    Frustum frustum;
    int width, height;   // the viewport, in pixels
    // The exact-visibility oracle's answer for this frame, when the caller
    // computed one (evaluation/oracle.h); only the `ideal` reference uses it.
    const VisibilityTruth *truth;
    // A frame of the switch-off's probes (traversal/policies.h), whose
    // tests only decide whether testing resumes: a strategy may prepare it
    // more cheaply (cheaper occluders), as long as its answers stay
    // conservative.
    bool probe = false;

    // The box's footprint in this frame (camera/footprint.h).
    std::optional<Footprint> footprint(const Aabb &box) const
    {
        return box_footprint(view_projection, camera.position, box, width, height);
    }

    // What every occlusion test does first: `t` is view_culled when its box
    // lies outside the frustum, visible untested when the box has no
    // footprint (it holds the eye or crosses the near plane), and visible
    // until shown occluded otherwise. Returns the footprint to test, or
    // nothing when t's answer is settled.
    std::optional<Footprint> occlusion_candidate(NodeTest &t) const;
};

// One node to test, and the answer.
struct NodeTest {
    std::uint32_t node = 0;
    Aabb box;                 // the node's bounds
    bool leaf = false;
    Visibility result = Visibility::visible;   // out
    bool test_below = true;                    // out, with visible: see above
};

struct CullerStats {
    std::uint32_t passes = 0;   // occlusion passes (or map builds) since begin_frame
};

class Culler {
public:
    virtual ~Culler() = default;
    virtual void begin_frame(const Frame &frame) = 0;
    // Answers every test, in the order given (front to back).
    virtual void test(std::vector<NodeTest> &tests) = 0;
    // The caller drew leaf `node`.
    virtual void rendered(std::uint32_t node) { (void)node; }
    virtual CullerStats stats() const { return {}; }
    // A sentence for the run's summary about what the figures do not show
    // (frames it could not cull as it claims to, work done on the way); empty: none.
    virtual std::string note() const { return {}; }
};

}  // namespace occu
