// SPDX-License-Identifier: MIT
#include "strategies/zhang_hierarchical_occlusion_maps/hierarchical_occlusion_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace occu {

namespace {
// 1 - v the same way for opacities and thresholds, so that o >= O_0 gives
// transparency(o) <= transparency(O_0) (both roundings are monotone).
float transparency_of(float opacity)
{
    if (!(opacity > 0.0f))   // NaN too: uncovered
        return 1.0f;
    if (opacity >= 1.0f)
        return 0.0f;
    return float(1.0 - double(opacity));
}
}  // namespace

// --- HierarchicalOcclusionMap ----------------------------------------------

void HierarchicalOcclusionMap::build(int width, int height, const float *opacity)
{
    layout_.reset(width, height);
    transparency_.resize(layout_.texels());   // within capacity once sized
    if (!layout_.levels())
        return;
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    for (std::size_t i = 0; i < pixels; ++i)
        transparency_[i] = transparency_of(opacity[i]);
    for (int k = 1; k < layout_.levels(); ++k) {
        // A level k - 1 texel (cx, cy) covers min(side, width - cx side)
        // columns of level-0 pixels, side = 2^(k - 1); rows alike.
        const int side = 1 << (k - 1);
        const int below_w = layout_.width(k - 1), below_h = layout_.height(k - 1);
        auto columns = [&](int cx) { return std::min(side, width - cx * side); };
        auto rows = [&](int cy) { return std::min(side, height - cy * side); };
        for (int y = 0; y < layout_.height(k); ++y) {
            for (int x = 0; x < layout_.width(k); ++x) {
                const int cx1 = std::min(2 * x + 2, below_w), cy1 = std::min(2 * y + 2, below_h);
                double sum = 0.0, area = 0.0;
                for (int cy = 2 * y; cy < cy1; ++cy) {
                    for (int cx = 2 * x; cx < cx1; ++cx) {
                        const double a = double(columns(cx)) * double(rows(cy));
                        sum += a * double(transparency_[layout_.index(k - 1, cx, cy)]);
                        area += a;
                    }
                }
                transparency_[layout_.index(k, x, y)] = float(sum / area);
            }
        }
    }
}

double HierarchicalOcclusionMap::level_threshold(double opacity_threshold, int k)
{
    return 1.0 - std::ldexp(1.0 - opacity_threshold, -2 * k);
}

bool HierarchicalOcclusionMap::overlaps(const PixelRect &rect, float opacity_threshold,
                                        std::uint64_t *texels_visited) const
{
    // 1 - O_k = (1 - O_0) / 4^k: scaling by a power of two is exact. A NaN
    // threshold settles nothing.
    std::array<float, PyramidLayout::max_levels> max_transparency{};
    const float level0 = std::isnan(opacity_threshold) ? std::nanf("") : transparency_of(opacity_threshold);
    for (int k = 0; k < layout_.levels(); ++k)
        max_transparency[std::size_t(k)] = std::ldexp(level0, -2 * k);
    std::uint64_t visited = 0;
    const bool result = all_pixels_settle(
        layout_, rect,
        [&](int k, std::size_t i) { return transparency_[i] <= max_transparency[std::size_t(k)]; }, visited);
    if (texels_visited)
        *texels_visited += visited;
    return result;
}

// --- DepthEstimationBuffer -------------------------------------------------

DepthEstimationBuffer::DepthEstimationBuffer(int regions_x, int regions_y)
    : regions_x_(regions_x), regions_y_(regions_y)
{
    if (regions_x < 1 || regions_y < 1 || regions_x > PyramidLayout::max_side || regions_y > PyramidLayout::max_side)
        throw std::invalid_argument("depth estimation buffer of " + std::to_string(regions_x) + "x" +
                                    std::to_string(regions_y) + " regions: need 1 to " +
                                    std::to_string(PyramidLayout::max_side) + " a side");
    farthest_.assign(std::size_t(regions_x) * std::size_t(regions_y), 1.0f);
}

void DepthEstimationBuffer::build(int width, int height, const float *occluder_depth)
{
    if (width < 0 || height < 0 || width > PyramidLayout::max_side || height > PyramidLayout::max_side)
        throw std::invalid_argument("depth estimation buffer over " + std::to_string(width) + "x" +
                                    std::to_string(height) + " pixels: sides must be 0 to " +
                                    std::to_string(PyramidLayout::max_side));
    width_ = width;
    height_ = height;
    // Farthest covered depth so far; none yet (-infinity) becomes 1 at the end.
    constexpr float none = -std::numeric_limits<float>::infinity();
    std::fill(farthest_.begin(), farthest_.end(), none);
    for (int y = 0; y < height; ++y) {
        float *row = farthest_.data() + std::size_t(region_y(y)) * std::size_t(regions_x_);
        const float *depth = occluder_depth + std::size_t(y) * std::size_t(width);
        for (int x = 0; x < width; ++x) {
            const float d = std::isnan(depth[x]) ? 1.0f : depth[x];   // NaN: covered, at 1
            if (d < 1.0f || std::isnan(depth[x])) {
                float &far = row[region_x(x)];
                far = std::max(far, d);
            }
        }
    }
    // Regions with pixels but none covered hold 1; regions without pixels
    // (more regions than pixels) are never touched: -infinity stays, so that
    // a rectangle of region indices may span them.
    for (int ry = 0; ry < regions_y_; ++ry)
        for (int rx = 0; rx < regions_x_; ++rx) {
            float &far = farthest_[std::size_t(ry) * std::size_t(regions_x_) + std::size_t(rx)];
            if (far == none && !region_pixels(rx, ry).empty())
                far = 1.0f;
        }
}

PixelRect DepthEstimationBuffer::regions_touched(const PixelRect &rect) const
{
    const PixelRect pixels = rect.clamped({0, 0, width_, height_});
    if (pixels.empty())
        return {};
    return {region_x(pixels.x0), region_y(pixels.y0), region_x(pixels.x1 - 1) + 1, region_y(pixels.y1 - 1) + 1};
}

PixelRect DepthEstimationBuffer::region_pixels(int rx, int ry) const
{
    // The first x with floor(x R / W) >= r is ceil(r W / R).
    auto first = [](int r, int regions, int size) {
        return int((std::int64_t(r) * size + regions - 1) / regions);
    };
    return {first(rx, regions_x_, width_), first(ry, regions_y_, height_), first(rx + 1, regions_x_, width_),
            first(ry + 1, regions_y_, height_)};
}

bool DepthEstimationBuffer::behind(const PixelRect &rect, float z) const
{
    const PixelRect regions = regions_touched(rect);
    if (regions.empty())
        return false;
    for (int ry = regions.y0; ry < regions.y1; ++ry)
        for (int rx = regions.x0; rx < regions.x1; ++rx)
            if (!(z > farthest(rx, ry)))
                return false;
    return true;
}

}  // namespace occu
