// SPDX-License-Identifier: MIT
// Visible pixels a culled frame lost, against the unculled frame of the
// same camera: what says a conservative strategy kept every visible pixel
// (occu-random-views, demos/random_views.cpp).
//
// Definition. A pixel is lost where the culled frame differs (any of its
// four RGBA8 bytes) from its reference: the same camera, viewport, GL state
// and clear colour, the leaves the culled frame drew in the order it drew
// them, then every leaf it left out. A leaf drawn later changes a pixel
// only where it is strictly in front of what is there (GL_LESS), so a lost
// pixel is one where a leaf the strategy culled is strictly nearer than
// everything it drew there: geometry the viewer sees that the culled frame
// shows wrongly (background, or what lies behind).
// See-through triangles (Mesh::occluder false) come last in both frames,
// sorted by distance, depth tested against the occluders and not writing
// depth (render/scene_renderer.h): a culled leaf's see-through surface
// changes a pixel only where no occluder drawn is nearer, and what lies
// behind a see-through surface counts as seen.
//
// Depth ties. Where faces tie in depth (coplanar faces of two leaves) the
// leaf drawn first keeps the pixel, so a frame that left out one of the two
// may differ from the unculled frame of another drawing order there
// without hiding anything nearer: which face shows is z-fighting, not
// visibility. The reference above puts what the strategy drew first, so
// such pixels are not lost; they are counted apart (`tied`) when the
// common traversal's unculled frame is given: pixels that differ from it
// but not from the reference. The measurement session applies this rule
// to every strategy it checks, for the programs and the integration tests
// alike (tests/integration/strategy_variants.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "camera/camera.h"

namespace occu {

class Hierarchy;
class SceneRenderer;

// Pixels in which two RGBA8 frames of `pixel_count` pixels differ.
std::uint64_t lost_pixels(const std::uint8_t *reference, const std::uint8_t *culled, std::size_t pixel_count);

// The reference above: clears colour and depth, loads `camera` and draws
// every leaf of `hierarchy`, those of `first` in their order, then the
// others in index order, then the see-through triangles of all of them as a
// frame draws them (render/scene_renderer.h); waits for it (glFinish). Draws into the current
// context with its state.
void draw_unculled_after(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera,
                         const std::vector<std::uint32_t> &first);

struct PixelLoss {
    std::uint64_t lost = 0;   // visible pixels lost (above)
    std::uint64_t tied = 0;   // pixels that differ from `unculled` through depth ties alone
};

// The pixels the culled frame in `frame` (the current context's pixels,
// `pixel_count` of them, just drawn with `camera`; `drawn`: its leaves in
// drawing order) lost. `unculled`, when given, is the frame the common
// traversal draws without culling: where the culled frame equals it
// nothing is lost and no reference is drawn (a pixel lost against the
// reference differs from it too, unless two leaves' colours coincide);
// otherwise the reference is drawn into the context, overwriting `frame`.
PixelLoss count_lost_pixels(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera,
                            const std::vector<std::uint32_t> &drawn, const std::uint8_t *unculled,
                            const std::uint8_t *frame, std::size_t pixel_count);

}  // namespace occu
