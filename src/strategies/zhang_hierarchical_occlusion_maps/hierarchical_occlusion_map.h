// SPDX-License-Identifier: MIT
// The two halves of Zhang, Manocha, Hudson and Hoff's occlusion test
// ([Zhang97], [Zhang98]; Moller and Haines, "Occlusion Culling Algorithms",
// section "The HOM Algorithm"): the overlap test in the image plane against a
// hierarchical occlusion map, and the depth test against a depth estimation
// buffer. "If an object passes both tests, the object is occluded."
//
// Conventions: window depth in [0, 1], 0 nearest, 1 far (cleared, nothing
// drawn); opacity in [0, 1], 1 fully covered by occluders. Images row by row,
// (0, 0) the lower left pixel, pixel (x, y) at y * width + x; rectangles are
// PixelRects of level-0 pixels, clamped to the image. An empty rectangle,
// or one outside the image, passes neither test (nothing is shown about it).
// Both structures keep their storage between builds.
//
// --- HierarchicalOcclusionMap --------------------------------------------
// Level 0 is the occlusion map, the occluders rendered white on black (any
// size; Zhang uses 256x256 for a 1024x1024 frame). "A hierarchy of occlusion
// maps ... is created by averaging" 2 x 2 blocks, down to 1 x 1 here (Zhang
// stops at 4x4 or 8x8; the test starts at a level about the rectangle's size,
// so only large rectangles meet the extra top levels). Level shapes as in
// maps/pyramid_layout.h; with odd sizes a texel is the mean opacity of the
// level-0 pixels it covers, of what exists (an area-weighted mean of its
// children: a plain mean would give a border child of one pixel column the
// weight of a full one).
//
// Opacity thresholds ("Example: Computation of opacity threshold values").
// A level-0 texel stands for m rendered pixels, of which n uncovered ones may
// pass as a negligible hole: O_0 = 1 - n/m. A level-k texel stands for 4^k m
// of them, and the same n holes give
//     O_k = 1 - n / (4^k m) = 1 - (1 - O_0) / 4^k,
// the paper's O_{k+1} = (3 + O_k) / 4. The thresholds grow towards the coarse
// levels (towards 1): the more a texel averages, the closer to opaque it must
// be to vouch for all of it. O_0 = 1 makes every O_k = 1: exact.
// What this guarantees: a level-k texel with mean opacity >= O_k over its
// c <= 4^k pixels has total transparency sum(1 - o) <= c (1 - O_0) / 4^k
// <= 1 - O_0, and as every term is >= 0, each of its pixels has o >= O_0.
// Conversely, when every pixel of a rectangle has o >= O_0, the descent ends
// at level 0 texels that all pass. So overlaps(rect, O_0) is exactly "every
// level-0 pixel of the rectangle has opacity >= O_0": the per-level
// thresholds make the hierarchy a shortcut of the level-0 test, never a
// looser test. O_0 < 1 is the knob of approximate culling: a level-0 pixel
// counts as covered when at most 1 - O_0 of it is uncovered (the negligible
// holes when a level-0 pixel stands for several rendered pixels), and a
// coarse texel with a few such pixels settles without a descent to them.
//
// Numbers: the map stores transparency, 1 - opacity, and compares it with
// 1 - O_k. A float sum or mean of non-negative values is zero only when
// every value is, so the exact test (transparency 0) survives rounding,
// where a float mean of opacities such as 1 - 2^-24 would round up to 1.
// Level 0 compares fl(1 - o) <= fl(1 - O_0), which is o >= O_0 for values in
// [0.5, 1] (exact subtractions). Coarse levels are area-weighted means taken
// in double and stored as float, so a coarse texel meets its threshold up to
// a relative rounding of about 1e-7 per level of 1 - O_0; with O_0 = 1, or
// with dyadic values (k / 2^j) on full texels, there is no rounding at all.
// Opacities outside [0, 1] are clamped; NaN counts as 0 (uncovered).
//
// --- DepthEstimationBuffer -----------------------------------------------
// "A software Z-buffer that divides the screen into a number of rectangular
// regions ... For each region the farthest z-value is stored"; an object
// "passes the depth test" when the nearest depth of its bounding box "is
// larger than the stored z-depth in all regions" its rectangle covers (64x64
// regions in [Zhang97]; here a constructor parameter). Region (rx, ry) of an
// R_x x R_y grid over a width x height image holds the pixels x with
// floor(x R_x / width) = rx, and the same for y (blocks of nearly equal size;
// with more regions than pixels some regions are empty).
// Input: the occluders' per-pixel depth at the occlusion map's resolution,
// 1 (the cleared value) or more where no occluder is: a pixel is covered
// when its depth is < 1. A region stores the farthest depth of its covered
// pixels; uncovered pixels are ignored, so a region of an occluder's far
// edge and the empty screen beside it keeps the occluder's depth (with them
// it would hold 1 and never pass). A region with no covered pixel stores 1
// (one without pixels, when regions outnumber pixels, -infinity: never
// touched); NaN depth counts as covered at depth 1. Zhang estimates each occluder's far
// depth by the farthest vertex of its bounding box, entered in every region
// its screen rectangle touches; the per-pixel farthest depth is never
// farther than that estimate (tighter), and needs the depth image.
// Conservative only together with the exact overlap test: behind() says
// nothing about uncovered pixels, so alone it may pass a rectangle over empty
// screen. When overlaps(rect, 1) holds, every pixel of the rectangle is
// covered, each region the rectangle touches holds the farthest depth of
// covered pixels that include the rectangle's there, and behind(rect, z)
// then means every pixel of the rectangle has an occluder nearer than z:
// occluded, pixel by pixel. (This needs the two images to agree: every pixel
// the occlusion map has fully opaque has depth < 1 here.) The converse fails
// only by the regions' coarseness: a covered pixel at or behind z in a
// touched region, outside the rectangle. With O_0 < 1 the combination is
// Zhang's approximate culling, no longer conservative.
#pragma once

#include "geometry/pixel_rect.h"
#include "maps/pyramid_layout.h"

#include <cstdint>
#include <vector>

namespace occu {

class HierarchicalOcclusionMap {
public:
    // One level: width x height transparencies (1 - opacity), row by row.
    struct Level {
        int width = 0, height = 0;
        const float *transparency = nullptr;
        float transparency_at(int x, int y) const
        {
            return transparency[std::size_t(y) * std::size_t(width) + std::size_t(x)];
        }
        float opacity_at(int x, int y) const { return 1.0f - transparency_at(x, y); }
    };

    // Rebuilds from the occlusion map `opacity` (width * height values). No
    // allocation once the storage has held an image this large.
    void build(int width, int height, const float *opacity);

    // O_k for the threshold O_0 at level 0: 1 - (1 - O_0) / 4^k.
    static double level_threshold(double opacity_threshold, int k);

    // The overlap test: does every level-0 pixel of `rect` have opacity >=
    // `opacity_threshold` (O_0; 1 = exact, every pixel fully covered; above
    // 1 acts as 1, NaN passes nothing)?
    // Hierarchical from the finest level at which the rectangle touches at
    // most 2 x 2 texels: a texel with opacity >= O_k settles its pixels, a
    // level-0 one below O_0 ends the test, others descend. `texels_visited`,
    // when given, grows by the texels tested.
    bool overlaps(const PixelRect &rect, float opacity_threshold = 1.0f,
                  std::uint64_t *texels_visited = nullptr) const;

    int width() const { return layout_.levels() ? layout_.width(0) : 0; }
    int height() const { return layout_.levels() ? layout_.height(0) : 0; }
    // Levels, 0 the occlusion map, levels() - 1 the 1 x 1 top.
    int levels() const { return layout_.levels(); }
    Level level(int k) const
    {
        return {layout_.width(k), layout_.height(k), transparency_.data() + layout_.offset(k)};
    }

private:
    PyramidLayout layout_;
    std::vector<float> transparency_;   // every level's mean transparency (layout_)
};

class DepthEstimationBuffer {
public:
    // A regions_x x regions_y grid (each >= 1).
    explicit DepthEstimationBuffer(int regions_x = 64, int regions_y = 64);

    // Rebuilds from the occluders' depth (width * height values, >= 1 where
    // no occluder covers the pixel). No allocation after construction.
    void build(int width, int height, const float *occluder_depth);

    // The depth test: is z strictly behind (greater than) the farthest
    // covered depth of every region that `rect` (clamped to the image)
    // touches? Occlusion only together with the exact overlap test (above).
    bool behind(const PixelRect &rect, float z) const;

    int regions_x() const { return regions_x_; }
    int regions_y() const { return regions_y_; }
    int width() const { return width_; }
    int height() const { return height_; }
    // The farthest covered depth of region (rx, ry): 1 when none of its
    // pixels is covered, -infinity when it has no pixels (more regions than
    // pixels: the rectangle of regions a rectangle touches may span such
    // regions, and they must not fail it).
    float farthest(int rx, int ry) const
    {
        return farthest_[std::size_t(ry) * std::size_t(regions_x_) + std::size_t(rx)];
    }
    // The regions holding the pixels of `rect` (clamped to the image), as a
    // rectangle of region indices.
    PixelRect regions_touched(const PixelRect &rect) const;
    // The pixels of region (rx, ry) (empty when it has none).
    PixelRect region_pixels(int rx, int ry) const;

private:
    int region_x(int x) const { return int(std::int64_t(x) * regions_x_ / width_); }
    int region_y(int y) const { return int(std::int64_t(y) * regions_y_ / height_); }
    int regions_x_, regions_y_;
    int width_ = 0, height_ = 0;
    std::vector<float> farthest_;   // regions_x * regions_y, row by row
};

}  // namespace occu
