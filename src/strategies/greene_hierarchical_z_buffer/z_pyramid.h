// SPDX-License-Identifier: MIT
// The Z-pyramid of Greene, Kass and Miller's hierarchical Z-buffer
// ([Greene93], in Moller and Haines, "Occlusion Culling Algorithms", section
// "Hierarchical Z-Buffering and the Hierarchical Visibility Algorithm",
// Figure 6): level 0 is a depth image; "at all other levels, each z-value is
// the farthest z in the corresponding 2x2 window of the adjacent finer
// level", so a texel holds the farthest depth of all the pixels below it.
// Built from a finished depth image each time, as in Greene's variant that
// reads back the Z-buffer of a partly rendered frame; not updated pixel by
// pixel.
//
// Conventions: window depth in [0, 1], 0 nearest, 1 far (cleared, nothing
// drawn); a NaN depth is stored as 1. Images row by row, (0, 0) the lower
// left pixel, pixel (x, y) at y * width + x. Any width and height: the level
// shapes of maps/pyramid_layout.h (odd sizes: the last column's or row's
// texel is the farthest of what it covers), down to 1 x 1.
//
// The test (the same section): a rectangle of pixels at nearest depth z is
// occluded when z is strictly behind (greater than) the stored depth of every
// pixel in it. It starts at the finest level at which the rectangle touches
// at most 2 x 2 texels; a texel nearer than z settles its pixels, one at
// level 0 that is not nearer than z is a visible pixel (the test ends), any
// other descends to its children inside the rectangle. The result equals
// the pixel-by-pixel comparison; densely occluded rectangles take a few
// comparisons.
#pragma once

#include "geometry/pixel_rect.h"
#include "maps/pyramid_layout.h"

#include <cstdint>
#include <vector>

namespace occu {

class ZPyramid {
public:
    // One level: width x height depths, row by row.
    struct Level {
        int width = 0, height = 0;
        const float *depth = nullptr;
        float at(int x, int y) const { return depth[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
    };

    // Rebuilds from `depth` (width * height values). Storage is kept between
    // builds: no allocation once it has held an image this large.
    void build(int width, int height, const float *depth);

    // True when every pixel of `rect` (clamped to the image) has stored
    // depth < z. An empty rectangle, or one outside the image, gives false
    // (not shown occluded). `texels_visited`, when given, grows by the
    // texels the test compared.
    bool occluded(const PixelRect &rect, float z, std::uint64_t *texels_visited = nullptr) const;

    int width() const { return layout_.levels() ? layout_.width(0) : 0; }
    int height() const { return layout_.levels() ? layout_.height(0) : 0; }
    // Levels, 0 the image, levels() - 1 the 1 x 1 top (0 before a build or
    // for an empty image).
    int levels() const { return layout_.levels(); }
    Level level(int k) const { return {layout_.width(k), layout_.height(k), farthest_.data() + layout_.offset(k)}; }

private:
    PyramidLayout layout_;
    std::vector<float> farthest_;   // every level's farthest depths (layout_)
};

}  // namespace occu
