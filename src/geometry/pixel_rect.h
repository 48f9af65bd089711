// Rectangles of pixels. A PixelRect holds the pixels (x, y) with
// x0 <= x < x1 and y0 <= y < y1; pixel (x, y) covers [x, x + 1) x [y, y + 1)
// and has its centre at (x + 0.5, y + 0.5). Empty when x0 >= x1 or y0 >= y1.
#pragma once

#include <algorithm>
#include <cstdint>

namespace occu {

struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

    bool empty() const { return x0 >= x1 || y0 >= y1; }
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    std::int64_t area() const { return empty() ? 0 : std::int64_t(width()) * std::int64_t(height()); }
    bool overlaps(const PixelRect &o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
    PixelRect clamped(const PixelRect &bounds) const
    {
        return {std::clamp(x0, bounds.x0, bounds.x1), std::clamp(y0, bounds.y0, bounds.y1),
                std::clamp(x1, bounds.x0, bounds.x1), std::clamp(y1, bounds.y0, bounds.y1)};
    }
    // The pixels of a map whose pixel (mx, my) covers this rectangle's
    // pixels [k mx, k mx + k) x [k my, k my + k): every map pixel that holds
    // one of these pixels (so a test over it is conservative).
    PixelRect to_map(int k) const
    {
        auto down = [k](int v) { return v >= 0 ? v / k : -((-v + k - 1) / k); };
        auto up = [k](int v) { return v >= 0 ? (v + k - 1) / k : -((-v) / k); };
        return {down(x0), down(y0), up(x1), up(y1)};
    }
    bool operator==(const PixelRect &o) const { return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1; }
};

}  // namespace occu
