// ID rendering: each leaf drawn in a flat colour that encodes its index,
// depth tested, then read back, so that every pixel names the leaf seen
// there. The oracle (exact visibility), first-hit occluder selection and
// the minimum-occluder-set preprocessing's redundancy removal (Poon and
// Wang, section 4.3) all read scenes this way.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.h"
#include "render/scene_renderer.h"

namespace occu {

// Draws `leaves` into the current framebuffer's lower-left width x height
// pixels (clobbering colour and depth there; the viewport is restored) and
// returns, per pixel (rows bottom-up), the leaf index + 1 seen there, 0 for
// background. Indices must be below 2^24 - 1.
std::vector<std::uint32_t> render_leaf_ids(const SceneRenderer &renderer, const Camera &camera,
                                           const std::vector<std::uint32_t> &leaves, int width, int height);

}  // namespace occu
