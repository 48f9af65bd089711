// SPDX-License-Identifier: MIT
// The opacity map of Poon and Wang (section 5.1): a summed-area table of the
// occluders' coverage bitmap, with a row and a column of zeros in front, so
// that the coverage of any rectangle takes three additions/subtractions
// (the opacity function, section 5.2).
//
// Coordinates as in the paper: the bitmap's pixels are (x, y) with
// 1 <= x <= width, 1 <= y <= height, (1, 1) the lower left; OP(0, y) =
// OP(x, 0) = 0; a rectangle (x1, x2, y1, y2) means x1 < x <= x2, y1 < y <= y2.
#pragma once

#include <cstdint>
#include <vector>

namespace occu {

class OpacityMap {
public:
    // `covered`: width * height bytes, row 0 the bottom row; non-zero = covered.
    OpacityMap(int width, int height, const std::vector<std::uint8_t> &covered);

    int width() const { return width_; }
    int height() const { return height_; }

    // OP(x, y): covered pixels in the rectangle from (1, 1) to (x, y).
    std::uint32_t opacity(int x, int y) const { return op_[std::size_t(y) * std::size_t(width_ + 1) + std::size_t(x)]; }

    // OPF(x1, x2, y1, y2): covered pixels with x1 < x <= x2, y1 < y <= y2
    // (0 <= x1 <= x2 <= width, 0 <= y1 <= y2 <= height).
    std::uint32_t covered(int x1, int x2, int y1, int y2) const
    {
        return opacity(x1, y1) - opacity(x1, y2) - opacity(x2, y1) + opacity(x2, y2);
    }

    // The overlap test: is the rectangle covered, but for at most
    // `tolerance` pixels (the approximate overlap test; 0 is exact)?
    bool overlaps_fully(int x1, int x2, int y1, int y2, std::uint32_t tolerance = 0) const
    {
        const auto area = std::uint32_t(x2 - x1) * std::uint32_t(y2 - y1);
        return covered(x1, x2, y1, y2) + tolerance >= area;
    }

    // The adaptive overlap test's coverage ratio: covered / area (1 for an
    // empty rectangle).
    double coverage_ratio(int x1, int x2, int y1, int y2) const;

private:
    int width_, height_;
    std::vector<std::uint32_t> op_;   // (width + 1) x (height + 1), row and column 0 zero
};

}  // namespace occu
