// SPDX-License-Identifier: MIT
// The scalar loops: the reference the AVX2 loops must equal bit for bit.
#include "raster/raster_kernels.h"

#include <algorithm>

namespace occu::raster {

void fill_scalar(const PolygonSetup &s, const TileBuffer &buffer)
{
    Band band;
    for (int y8 = s.y0 / tile_size * tile_size; y8 < s.y1; y8 += tile_size) {
        band_terms(s, s.edges, y8 > s.y0 ? y8 : s.y0, y8 + tile_size < s.y1 ? y8 + tile_size : s.y1, &band);
        const bool all_rows = band.row0 == y8 && band.row1 == y8 + tile_size;
        for (int x8 = s.x0 / tile_size * tile_size; x8 < s.x1; x8 += tile_size) {
            const Cover cover = tile_cover(s, band, x8);
            if (cover == Cover::none)
                continue;
            const std::size_t t = tile_index(buffer, x8, y8);
            if (tile_nearest_depth(s, band, x8) >= buffer.farthest_bound[t])
                continue;
            float *tile = tile_at(buffer, t);
            bool wrote = false;
            for (int y = band.row0; y < band.row1; ++y) {
                const float fy = float(y);
                float edge_term[max_edges];
                for (int e = 0; e < s.edges; ++e)
                    edge_term[e] = s.eb[e] * fy + s.ec[e];
                const float depth_term = s.zb * fy + s.zc;
                float *row = tile + (y - y8) * tile_size;
                for (int lane = 0; lane < tile_size; ++lane) {
                    const float fx = float(x8 + lane);
                    bool inside = true;
                    if (cover == Cover::part)
                        for (int e = 0; e < s.edges; ++e)
                            inside &= s.ea[e] * fx + edge_term[e] >= 0.0f;
                    const float z = std::min(s.za * fx + depth_term, s.zcap);
                    if (inside && z < row[lane]) {
                        row[lane] = z;
                        wrote = true;
                    }
                }
            }
            if (wrote)
                buffer.dirty[t] = 1;
            if (cover == Cover::whole && all_rows) {
                // Every pixel is now no farther than the polygon's farthest here.
                const float farthest = tile_farthest_depth(s, band, x8);
                if (farthest < buffer.farthest_bound[t])
                    buffer.farthest_bound[t] = farthest;
            }
        }
    }
}

void crossing_columns_scalar(const Crossings &c, int y, std::int32_t *column)
{
    constexpr double eps = 0x1p-52;
    for (int l = 0; l < c.lanes; ++l) {
        const double v = double(y) + c.offset[l];
        const double bv = c.slope[l] * v, crossing = c.start[l] + bv;
        const double slack = 8.0 * eps * ((std::fabs(c.start[l]) + std::fabs(bv)) + std::fabs(crossing));
        if (c.rising[l]) {
            const double x = (crossing + slack) * c.k - 0.5;
            const double first = std::ceil(x + 4.0 * eps * (std::fabs(x) + 1.0));
            column[l] = first <= double(c.c_hi) ? std::int32_t(first < double(c.c_lo) ? double(c.c_lo) : first)
                                                : c.c_hi + 1;
        } else {
            const double x = (crossing - slack) * c.k - 0.5;
            const double last = std::floor(x - 4.0 * eps * (std::fabs(x) + 1.0));
            column[l] = last >= double(c.c_lo) ? std::int32_t(last > double(c.c_hi) ? double(c.c_hi) : last)
                                               : c.c_lo - 1;
        }
    }
}

bool tile_behind_scalar(const float *tile, int c0, int c1, int r0, int r1, float z)
{
    for (int r = r0; r < r1; ++r)
        for (int c = c0; c < c1; ++c)
            if (!(tile[r * tile_size + c] < z))
                return false;
    return true;
}

}  // namespace occu::raster
