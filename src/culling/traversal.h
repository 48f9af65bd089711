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
    std::size_t batch = 16;
};

struct FrameStats {
    std::uint64_t triangles = 0;
    std::uint32_t leaves_drawn = 0;
    std::uint32_t nodes_tested = 0;
    std::uint32_t nodes_view_culled = 0;
    std::uint32_t nodes_occluded = 0;
    std::uint32_t passes = 0;
    std::vector<std::uint32_t> drawn;   // leaf node indices, in drawing order
};

// Draws one frame into the current context's bound framebuffer (the caller
// clears it and sets the camera's matrices) and returns what it did.
FrameStats render_hierarchy(const SceneRenderer &renderer, const Hierarchy &hierarchy, Culler &culler,
                            const Camera &camera, const TraversalOptions &options);

// Loads the camera's projection and view into GL's fixed-function matrices.
void load_camera(const Camera &camera);

}  // namespace occu
