// SPDX-License-Identifier: MIT
#include "strategies/greene_hierarchical_z_buffer/z_pyramid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace occu {

void ZPyramid::build(int width, int height, const float *depth)
{
    layout_.reset(width, height);
    farthest_.resize(layout_.texels());   // within capacity once sized
    if (!layout_.levels())
        return;
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    for (std::size_t i = 0; i < pixels; ++i)
        farthest_[i] = std::isnan(depth[i]) ? 1.0f : depth[i];
    for (int k = 1; k < layout_.levels(); ++k) {
        const int below_w = layout_.width(k - 1), below_h = layout_.height(k - 1);
        for (int y = 0; y < layout_.height(k); ++y) {
            for (int x = 0; x < layout_.width(k); ++x) {
                // The up to 2 x 2 texels below that exist.
                const int cx1 = std::min(2 * x + 2, below_w), cy1 = std::min(2 * y + 2, below_h);
                float far = -std::numeric_limits<float>::infinity();
                for (int cy = 2 * y; cy < cy1; ++cy)
                    for (int cx = 2 * x; cx < cx1; ++cx)
                        far = std::max(far, farthest_[layout_.index(k - 1, cx, cy)]);
                farthest_[layout_.index(k, x, y)] = far;
            }
        }
    }
}

bool ZPyramid::occluded(const PixelRect &rect, float z, std::uint64_t *texels_visited) const
{
    std::uint64_t visited = 0;
    // A texel nearer than z holds only pixels nearer than z (it is their
    // farthest); NaN z settles nothing.
    const bool result =
        all_pixels_settle(layout_, rect, [&](int, std::size_t i) { return farthest_[i] < z; }, visited);
    if (texels_visited)
        *texels_visited += visited;
    return result;
}

}  // namespace occu
