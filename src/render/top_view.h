// SPDX-License-Identifier: MIT
// A top view of a frame, like the papers' bird's-eye figures (Bartz et al.
// 1998, figures 1b and 2b): every leaf's footprint seen from above, coloured
// by what the strategy did with it, and the camera's position and view
// direction; with a title (strategy, frame, frame time, share culled) and a
// legend of the colours, in occu's own bitmap font (image/text.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "geometry/pixel_rect.h"
#include "image/text.h"
#include "spatial/hierarchy.h"

namespace occu {

// The top view's colours, RGB in [0, 1]: the map's and its legend's.
struct TopViewColour {
    float r, g, b;
    Rgba8 rgba8() const;
};
namespace top_view_colours {
constexpr TopViewColour drawn{0.16f, 0.66f, 0.24f};           // green
constexpr TopViewColour culled{0.97f, 0.80f, 0.08f};          // yellow: in the frustum, not drawn
constexpr TopViewColour outside{0.66f, 0.67f, 0.69f};         // grey: outside the view frustum
constexpr TopViewColour wrongly_culled{0.86f, 0.08f, 0.80f};  // magenta: visible (the oracle saw it), not drawn
constexpr TopViewColour camera{0.88f, 0.10f, 0.10f};          // red
}  // namespace top_view_colours

// Where the map goes in a top view of width x height pixels: a square
// between the title above it and the legend below it, in GL window
// coordinates (row 0 at the bottom).
PixelRect top_view_map_area(int width, int height);

// Draws into the current framebuffer: clears it white and draws the map
// into `area` (empty: the whole viewport), the scene's ground rectangle
// fitted with its proportions kept. Footprints outside the frustum first,
// then culled, drawn and wrongly culled ones (leaves the oracle saw that
// were not drawn), so that a footprint drawn or wrongly culled at any
// height shows.
void render_top_view(const Hierarchy &hierarchy, const Camera &camera, const std::vector<std::uint32_t> &drawn,
                     const std::vector<std::uint32_t> &wrongly_culled = {}, const PixelRect &area = {});

// What a top view's title and legend say.
struct TopViewCaption {
    std::string strategy;
    std::size_t frame = 0;
    double ms = 0.0;
    double culled_percent = 0.0;                  // the scene's triangles not drawn
    std::optional<double> efficiency_percent;     // occluded leaves culled / occluded leaves (with the oracle)
    std::optional<std::size_t> wrongly_culled;    // visible leaves not drawn (with the oracle)
};

// Writes the title above and the legend below the map of
// top_view_map_area into `image` (the top view read back, top row first).
void caption_top_view(ImageRef image, const TopViewCaption &caption);

}  // namespace occu
