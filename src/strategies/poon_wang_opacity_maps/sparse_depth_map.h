// SPDX-License-Identifier: MIT
// The sparse depth map of Poon and Wang (section 5.3): for each pixel of the
// occluders' depth map, how many pixels to the right the run of
// non-decreasing depth it belongs to goes on. Within such a run the farthest
// depth is at its end (its peak), so testing whether an occludee lies behind
// every occluder pixel of a row segment needs one comparison per run, not
// per pixel (section 5.4). Where depth alternates pixel by pixel no run is
// longer than two pixels and the map saves next to nothing; `worthwhile()`
// says so, and callers then compare pixel by pixel (the paper disables the
// map there).
//
// Depth grows with distance (window z). Coordinates: 0-based, row 0 the
// bottom row; a segment is x0 <= x <= x1.
#pragma once

#include <cstdint>
#include <vector>

namespace occu {

class SparseDepthMap {
public:
    SparseDepthMap(int width, int height, std::vector<float> depth);

    // True when the occludee's nearest depth `z_near` is strictly behind
    // every depth map value in the rectangle x0..x1, y0..y1 (inclusive).
    bool behind(float z_near, int x0, int x1, int y0, int y1) const;
    // The same, pixel by pixel (the reference, and what the map equals).
    bool behind_pixelwise(float z_near, int x0, int x1, int y0, int y1) const;

    // Mean run length above 2: the map skips enough to pay for itself.
    bool worthwhile() const { return mean_run_ > 2.0; }
    double mean_run_length() const { return mean_run_; }
    // Pixels from (x, y) to the end of its run, itself included (>= 1).
    std::uint16_t skip(int x, int y) const { return skip_[index(x, y)]; }

private:
    std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(width_) + std::size_t(x); }
    int width_, height_;
    std::vector<float> depth_;
    std::vector<std::uint16_t> skip_;
    double mean_run_ = 1.0;
};

}  // namespace occu
