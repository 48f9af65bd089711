// SPDX-License-Identifier: MIT
// The shape of an image pyramid built by 2x2 reduction, shared by the
// Z-pyramid of Greene, Kass and Miller
// (strategies/greene_hierarchical_z_buffer/z_pyramid.h) and the
// hierarchical occlusion map of Zhang et al.
// (strategies/zhang_hierarchical_occlusion_maps/hierarchical_occlusion_map.h),
// and the hierarchical rectangle test both run on it (Moller and Haines,
// "Occlusion Culling Algorithms": "Hierarchical Z-Buffering and the
// Hierarchical Visibility Algorithm" and "The HOM Algorithm").
//
// Level 0 is the image, width x height pixels (any sizes, not only powers of
// two). Level k + 1 has ceil(w_k / 2) x ceil(h_k / 2) texels, down to 1 x 1;
// texel (x, y) of level k + 1 reduces the up to 2 x 2 texels (2x + i, 2y + j),
// i, j in {0, 1}, of level k that exist (with an odd size the last column's
// or row's texel has only what is there). So texel (x, y) of level k holds
// the level-0 pixels [x 2^k, (x + 1) 2^k) x [y 2^k, (y + 1) 2^k) clamped to
// the image, its footprint, and level k has exactly ceil(width / 2^k) x
// ceil(height / 2^k) texels. Levels are stored one after another, row by row,
// row 0 the bottom row, texel (x, y) of level k at offset(k) + y w_k + x.
#pragma once

#include "geometry/pixel_rect.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace occu {

class PyramidLayout {
public:
    // Image sides are limited so that 2^k of every level fits an int.
    static constexpr int max_side = 1 << 24;
    static constexpr int max_levels = 26;

    // The levels of a width x height image (0 x 0: no levels).
    void reset(int width, int height)
    {
        if (width < 0 || height < 0 || width > max_side || height > max_side)
            throw std::invalid_argument("image pyramid of " + std::to_string(width) + "x" + std::to_string(height) +
                                        ": sides must be 0 to " + std::to_string(max_side));
        levels_ = 0;
        std::size_t offset = 0;
        if (width == 0 || height == 0)
            width = height = 0;
        else {
            for (int w = width, h = height;; w = (w + 1) / 2, h = (h + 1) / 2) {
                shapes_[std::size_t(levels_++)] = {w, h, offset};
                offset += std::size_t(w) * std::size_t(h);
                if (w == 1 && h == 1)
                    break;
            }
        }
        texels_ = offset;
    }

    int levels() const { return levels_; }
    int width(int k) const { return shapes_[std::size_t(k)].width; }
    int height(int k) const { return shapes_[std::size_t(k)].height; }
    std::size_t offset(int k) const { return shapes_[std::size_t(k)].offset; }
    std::size_t index(int k, int x, int y) const
    {
        return offset(k) + std::size_t(y) * std::size_t(width(k)) + std::size_t(x);
    }
    // Texels of all levels together.
    std::size_t texels() const { return texels_; }
    // The level-0 image as a rectangle (empty without levels).
    PixelRect image() const { return levels_ ? PixelRect{0, 0, width(0), height(0)} : PixelRect{}; }

    // The level-k texels whose footprints hold pixels of `pixels`, a
    // rectangle of level-0 pixels inside the image.
    static PixelRect texels_holding(const PixelRect &pixels, int k) { return pixels.to_map(1 << k); }

    // The level at which a hierarchical test of `pixels` (inside the image,
    // not empty) starts: the finest level at which they touch at most 2 x 2
    // texels. Texels there are about the rectangle's size (Greene starts at
    // "the coarsest Z-pyramid cell that encloses the face's screen
    // projection", Zhang at "the level in which the size of the pixel in the
    // HOM is approximately the size of the rectangle"); allowing 2 x 2
    // instead of 1 keeps a small rectangle that straddles a coarse texel
    // boundary from starting near the top.
    int start_level(const PixelRect &pixels) const
    {
        int k = 0;
        for (PixelRect t = pixels; t.width() > 2 || t.height() > 2; t = texels_holding(pixels, ++k)) {
        }
        return k;
    }

private:
    struct Shape {
        int width = 0, height = 0;
        std::size_t offset = 0;
    };
    std::array<Shape, max_levels> shapes_{};
    int levels_ = 0;
    std::size_t texels_ = 0;
};

namespace pyramid_detail {

template <class Settles>
bool all_settle(const PyramidLayout &layout, const PixelRect &pixels, int k, const PixelRect &texels,
                Settles &settles, std::uint64_t &visited)
{
    for (int y = texels.y0; y < texels.y1; ++y) {
        for (int x = texels.x0; x < texels.x1; ++x) {
            ++visited;
            if (settles(k, layout.index(k, x, y)))
                continue;
            if (k == 0)
                return false;
            // The children of (x, y) that hold pixels of the rectangle.
            const PixelRect below = PyramidLayout::texels_holding(pixels, k - 1);
            const PixelRect children{std::max(2 * x, below.x0), std::max(2 * y, below.y0),
                                     std::min(2 * x + 2, below.x1), std::min(2 * y + 2, below.y1)};
            if (!all_settle(layout, pixels, k - 1, children, settles, visited))
                return false;
        }
    }
    return true;
}

}  // namespace pyramid_detail

// The hierarchical test: is every level-0 pixel of `rect` (clamped to the
// image) settled? Starting at layout.start_level(rect), each texel touched is
// tested with settles(k, index): true settles all the pixels of its
// footprint; false at level 0 ends the test with false (early out); false at
// a coarser level descends into its children that hold pixels of the
// rectangle. `visited` grows by the texels tested. An empty rectangle (after
// clamping) gives false: nothing is shown about pixels that are not there,
// so a caller that culls on true stays conservative.
template <class Settles>
bool all_pixels_settle(const PyramidLayout &layout, const PixelRect &rect, Settles settles, std::uint64_t &visited)
{
    const PixelRect pixels = rect.clamped(layout.image());
    if (pixels.empty())
        return false;
    const int k = layout.start_level(pixels);
    return pyramid_detail::all_settle(layout, pixels, k, PyramidLayout::texels_holding(pixels, k), settles, visited);
}

}  // namespace occu
