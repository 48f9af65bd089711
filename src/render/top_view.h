// A top view of a frame, like the papers' bird's-eye figures (Bartz et al.
// 1998, figures 1b and 2b): every leaf's footprint seen from above, coloured
// by what the strategy did with it, and the camera's position and view
// direction.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.h"
#include "spatial/hierarchy.h"

namespace occu {

// Colours: outside the frustum dark grey, culled (occluded) yellow, drawn
// green, the camera red. Draws into the current framebuffer.
void render_top_view(const Hierarchy &hierarchy, const Camera &camera, const std::vector<std::uint32_t> &drawn);

}  // namespace occu
