// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/opacity_map.h"

#include <stdexcept>
#include <string>

namespace occu {

OpacityMap::OpacityMap(int width, int height, const std::vector<std::uint8_t> &covered)
    : width_(width), height_(height), op_(std::size_t(width + 1) * std::size_t(height + 1), 0)
{
    if (width < 0 || height < 0 || covered.size() != std::size_t(width) * std::size_t(height))
        throw std::invalid_argument("opacity map of " + std::to_string(width) + "x" + std::to_string(height) +
                                    " needs that many coverage values, got " + std::to_string(covered.size()));
    const std::size_t stride = std::size_t(width + 1);
    for (int y = 1; y <= height; ++y) {
        std::uint32_t row = 0;   // covered pixels of this row up to x
        for (int x = 1; x <= width; ++x) {
            row += covered[std::size_t(y - 1) * std::size_t(width) + std::size_t(x - 1)] != 0;
            op_[std::size_t(y) * stride + std::size_t(x)] = op_[std::size_t(y - 1) * stride + std::size_t(x)] + row;
        }
    }
}

double OpacityMap::coverage_ratio(int x1, int x2, int y1, int y2) const
{
    const double area = double(x2 - x1) * double(y2 - y1);
    return area > 0 ? double(covered(x1, x2, y1, y2)) / area : 1.0;
}

}  // namespace occu
