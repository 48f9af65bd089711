// SPDX-License-Identifier: MIT
// The scalar loops: the reference the AVX2 loops must equal bit for bit.
#include "raster/raster_kernels.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

namespace {

// Where a line crosses sample row v, as partial_rows_runs' column.
std::int32_t line_column(const Crossings &c, int line, double v)
{
    constexpr double eps = 0x1p-52;
    const double start = c.start[line], bv = c.slope[line] * v, crossing = start + bv;
    if (c.level[line]) {
        const bool holds = crossing - 8.0 * eps * (std::fabs(start) + std::fabs(bv)) >= 0.0;
        return holds ? c.c_lo : c.c_hi + 1;
    }
    const double slack = 8.0 * eps * ((std::fabs(start) + std::fabs(bv)) + std::fabs(crossing));
    if (c.rising[line]) {
        const double x = (crossing + slack) * c.k - 0.5;
        const double first = std::ceil(x + 4.0 * eps * (std::fabs(x) + 1.0));
        return first <= double(c.c_hi) ? std::int32_t(first < double(c.c_lo) ? double(c.c_lo) : first) : c.c_hi + 1;
    }
    const double x = (crossing - slack) * c.k - 0.5;
    const double last = std::floor(x - 4.0 * eps * (std::fabs(x) + 1.0));
    return last >= double(c.c_lo) ? std::int32_t(last > double(c.c_hi) ? double(c.c_hi) : last) : c.c_lo - 1;
}

}  // namespace

unsigned partial_rows_runs_scalar(const Crossings &c, int y, RowsRuns &out)
{
    const int k = c.k;
    unsigned rows = 0;
    for (int e = 0; e < 3; ++e)
        out.band_lanes[e] = 0;
    for (int r = 0; r < rows_at_once(k); ++r) {
        const int l0 = r * k;
        int first = c.c_hi + 1, last = c.c_lo - 1, whole_first = c.c_lo, whole_last = c.c_hi;
        const auto extend = [&](int lo, int hi) {
            if (lo <= hi) {
                first = std::min(first, lo);
                last = std::max(last, hi);
            }
            return lo <= hi;
        };
        for (int j = 0; j < k; ++j) {
            const int l = l0 + j;
            const double v = double(y + r) + c.lane_offset[l];
            // Edge e's bound: from its column on where it rises, else up to it.
            std::int32_t column[max_edges], lower[max_edges], upper[max_edges];
            int lo = c.c_lo, hi = c.c_hi;
            for (int e = 0; e < c.edges; ++e) {
                column[e] = line_column(c, e, v);
                const bool rises = c.rising_edges >> e & 1;
                lower[e] = rises ? column[e] : c.c_lo;
                upper[e] = rises ? c.c_hi : column[e];
                lo = std::max(lo, lower[e]);
                hi = std::min(hi, upper[e]);
            }
            out.held_lo[l] = lo;
            out.held_hi[l] = hi;
            whole_first = std::max(whole_first, lo);
            whole_last = std::min(whole_last, hi);
            extend(lo, hi);
            for (int e = 0; e < 3; ++e) {
                if (!(c.candidates >> e & 1))
                    continue;
                const int reach = line_column(c, c.reach_line[e], v);
                int band_lo = c.rising_edges >> e & 1 ? reach : column[e] + 1;
                int band_hi = c.rising_edges >> e & 1 ? column[e] - 1 : reach;
                for (int o = 0; o < c.edges; ++o)
                    if (o != e) {
                        band_lo = std::max(band_lo, lower[o]);
                        band_hi = std::min(band_hi, upper[o]);
                    }
                out.band_lo[e][l] = band_lo;
                out.band_hi[e][l] = band_hi;
                if (extend(band_lo, band_hi))
                    out.band_lanes[e] |= 1u << l;
            }
        }
        out.first[l0] = first;
        out.last[l0] = last;
        out.whole_first[l0] = whole_first;
        out.whole_last[l0] = whole_last;
        rows |= unsigned(first <= last) << r;
    }
    return rows;
}

namespace {

// x << n, and 0 for n >= 32 (as AVX2's shifts by a count in a register).
inline std::uint32_t shift_left(std::uint32_t x, int n) { return n < 32 ? x << n : 0; }
inline std::uint32_t shift_right(std::uint32_t x, int n) { return n < 32 ? x >> n : 0; }

// z widened by `error` and rounded up (DepthRasterizer::merge_partial's depth bound).
inline float widened(float z, double error) { return partial_next_up(float(double(z) + error)); }

}  // namespace

unsigned run_masks_scalar(const std::int32_t *run_lo, const std::int32_t *run_hi, int k, int x8, MaskRow &out)
{
    unsigned lanes = 0;
    for (int lane = 0; lane < tile_size; ++lane) {
        const int first = (x8 + lane) * k;
        std::uint32_t lo = 0, hi = 0;
        for (int j = 0; j < k; ++j) {
            // Columns [s, t) of the pixel's k: bits (1 << t) - (1 << s).
            const int s = std::min(std::max(run_lo[j] - first, 0), k);
            const int t = std::min(std::max(run_hi[j] + 1 - first, s), k);
            const std::uint32_t bits = (std::uint32_t(1) << t) - (std::uint32_t(1) << s);
            const int b = j * k;
            lo |= shift_left(bits, b);
            hi |= shift_left(bits, b >= 32 ? b - 32 : 32) | shift_right(bits, b < 32 ? 32 - b : 32);
        }
        out.lo[lane] = lo;
        out.hi[lane] = hi;
        lanes |= unsigned((lo | hi) != 0) << lane;
    }
    return lanes;
}

unsigned partial_row_depth_scalar(PartialRow &r, const float *depth)
{
    unsigned lanes = 0;
    for (int lane = 0; lane < tile_size; ++lane) {
        r.z[lane] = widened(std::min(r.za * float(r.x8 + lane) + r.depth_term, r.zcap), r.depth_error);
        lanes |= unsigned(r.z[lane] < depth[lane]) << lane;
    }
    return lanes;
}

unsigned merge_partial_row_scalar(const PartialRow &r, const PartialTileRow &t)
{
    const int k = r.k;
    const float fy = float(r.y);
    unsigned wrote = 0;
    for (int lane = 0; lane < tile_size; ++lane) {
        const float fx = float(r.x8 + lane);
        std::uint32_t lo = r.held.lo[lane], hi = r.held.hi[lane];
        float z = r.z[lane];
        for (int a = 0; a < r.across_count; ++a) {
            // Within the band beyond a shared edge, inside the triangle
            // across: held, at the farther of the two triangles' depths.
            const PartialAcross &n = *r.across[a];
            std::uint32_t in_lo = 0, in_hi = 0;
            for (int j = 0; j < k; ++j) {
                const float v = fy + r.offset[j];
                for (int i = 0; i < k; ++i) {
                    const float u = fx + r.offset[i];
                    const bool in = n.ea[0] * u + n.eb[0] * v >= n.held[0] && n.ea[1] * u + n.eb[1] * v >= n.held[1];
                    const int b = j * k + i;
                    in_lo |= shift_left(std::uint32_t(in), b);
                    in_hi |= shift_left(std::uint32_t(in), b >= 32 ? b - 32 : 32);
                }
            }
            in_lo &= r.band[a].lo[lane];
            in_hi &= r.band[a].hi[lane];
            lo |= in_lo;
            hi |= in_hi;
            const PolygonSetup &d = n.depth;
            const float across_z = widened(std::min(d.za * fx + (d.zb * fy + d.zc), d.zcap), n.depth_error);
            z = (in_lo | in_hi) != 0 ? std::max(z, across_z) : z;
        }
        const float depth = t.depth[lane];
        if (!((lo | hi) != 0 && z < depth))
            continue;
        const std::uint32_t old_lo = t.mask_lo[lane], old_hi = t.mask_hi[lane];
        const float farthest = (old_lo | old_hi) != 0 ? std::max(t.partial_depth[lane], z) : z;
        lo |= old_lo;
        hi |= old_hi;
        if (lo != r.full_lo || hi != r.full_hi) {
            t.mask_lo[lane] = lo;
            t.mask_hi[lane] = hi;
            t.partial_depth[lane] = farthest;
            wrote |= 2;
            continue;
        }
        // Every sample is held no farther than `farthest`; the layer
        // starts again empty, whether or not it was nearer.
        t.mask_lo[lane] = t.mask_hi[lane] = 0;
        if (farthest < depth) {
            t.depth[lane] = farthest;
            wrote |= 1;
        }
    }
    return wrote;
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
