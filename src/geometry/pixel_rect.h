// SPDX-License-Identifier: MIT
// Rectangles of pixels. A PixelRect holds the pixels (x, y) with
// x0 <= x < x1 and y0 <= y < y1; pixel (x, y) covers [x, x + 1) x [y, y + 1)
// and has its centre at (x + 0.5, y + 0.5). Empty when x0 >= x1 or y0 >= y1.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

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

// Groups of at most `limit` of `members` (indices into `rects`), greedy in
// the order given: each rectangle joins the first group it fits, where it
// fits when the group has room and, unless `overlap` is allowed, overlaps
// none of the group's rectangles. The groups of occlusion passes, one
// tile per rectangle, so that no tile counts another's fragments.
inline std::vector<std::vector<std::size_t>> disjoint_groups(const std::vector<PixelRect> &rects,
                                                             std::vector<std::size_t> members, std::size_t limit,
                                                             bool overlap = false)
{
    std::vector<std::vector<std::size_t>> groups;
    while (!members.empty()) {
        std::vector<std::size_t> group, later;
        for (std::size_t i : members) {
            bool fits = group.size() < limit;
            for (std::size_t k = 0; fits && !overlap && k < group.size(); ++k)
                fits = !rects[i].overlaps(rects[group[k]]);
            (fits ? group : later).push_back(i);
        }
        groups.push_back(std::move(group));
        members.swap(later);
    }
    return groups;
}

}  // namespace occu
