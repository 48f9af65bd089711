// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/sparse_depth_map.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace occu {

SparseDepthMap::SparseDepthMap(int width, int height, std::vector<float> depth)
    : width_(width), height_(height), depth_(std::move(depth)), skip_(depth_.size(), 1)
{
    if (width < 0 || height < 0 || depth_.size() != std::size_t(width) * std::size_t(height))
        throw std::invalid_argument("sparse depth map of " + std::to_string(width) + "x" + std::to_string(height) +
                                    " needs that many depth values, got " + std::to_string(depth_.size()));
    if (width > std::numeric_limits<std::uint16_t>::max())
        throw std::invalid_argument("sparse depth map rows are limited to 65535 pixels");
    // Right to left (the paper's construction order): a pixel continues the
    // run of its right neighbour when the depth does not fall towards it.
    std::size_t runs = 0;
    for (int y = 0; y < height; ++y) {
        for (int x = width - 1; x >= 0; --x) {
            const bool continues = x + 1 < width && depth_[index(x, y)] <= depth_[index(x + 1, y)];
            skip_[index(x, y)] = continues ? std::uint16_t(skip_[index(x + 1, y)] + 1) : 1;
            runs += !continues;
        }
    }
    mean_run_ = runs ? double(depth_.size()) / double(runs) : 1.0;
}

bool SparseDepthMap::behind(float z_near, int x0, int x1, int y0, int y1) const
{
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1;) {
            // The run from x reaches x + skip - 1; its farthest value inside
            // the segment is at the segment's or the run's end.
            const int end = x + skip_[index(x, y)] - 1;
            if (!(z_near > depth_[index(std::min(end, x1), y)]))
                return false;
            x = end + 1;
        }
    }
    return true;
}

bool SparseDepthMap::behind_pixelwise(float z_near, int x0, int x1, int y0, int y1) const
{
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
            if (!(z_near > depth_[index(x, y)]))
                return false;
    return true;
}

}  // namespace occu
