// Visible pixels a culled frame lost, against the unculled frame of the
// same camera: what says a conservative strategy kept every visible pixel
// (occu-random-views, demos/random_views.cpp).
//
// Definition. Both frames are drawn into the same context with the same
// camera, viewport, GL state and clear colour, and with the same drawing
// order for the leaves both draw: the unculled frame is the culled one plus
// the leaves it did not draw. A pixel is lost where the two frames differ
// (any of its four RGBA8 bytes). A culled frame only leaves leaves out, so
// such a pixel is one where a leaf it left out passes the depth test in the
// unculled frame: geometry the viewer sees that the culled frame shows
// wrongly (background, or what lies behind).
//
// Depth ties. Where faces tie in depth the leaf drawn first keeps the pixel
// (GL_LESS), so the order matters: for a strategy drawn by the common
// traversal (traversal/traversal.h) the unculled frame is the traversal's
// with the strategy `none` and the same batches (it draws the leaves in the
// same order, front to back); a strategy that orders the frame itself
// (Culler::orders_frame, e.g. chc) draws in an order of its own, so its
// unculled frame is draw_unculled_after(its leaves): its leaves in its
// order, then the others. In that reference a leaf it culled changes a
// pixel only where it is strictly in front of what it drew there: where it
// was visible (as tests/integration/frame_comparison.h does).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "camera/camera.h"

namespace occu {

class Hierarchy;
class SceneRenderer;

// Pixels in which two RGBA8 frames of `pixel_count` pixels differ: the
// visible pixels `culled` lost when `unculled` is its reference (above).
std::uint64_t lost_pixels(const std::uint8_t *unculled, const std::uint8_t *culled, std::size_t pixel_count);

// The reference of a frame a strategy ordered itself: clears colour and
// depth, loads `camera` and draws every leaf of `hierarchy`, those of
// `first` in their order, then the others in index order; waits for it
// (glFinish). Draws into the current context with its state.
void draw_unculled_after(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera,
                         const std::vector<std::uint32_t> &first);

}  // namespace occu
