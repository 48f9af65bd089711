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
    const int rows_here = std::min(rows_at_once(k), c.y_end - y);
    for (int r = 0; r < rows_here; ++r) {
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

// Eight pixels' masks, a lane each.
struct MaskRow {
    std::uint32_t lo[tile_size], hi[tile_size];
};

// The runs lo[j] .. hi[j] of sample rows j < k in depth pixels x8 .. x8 +
// 7 as their masks; returns the lanes with a sample.
unsigned run_masks(const std::int32_t *run_lo, const std::int32_t *run_hi, int k, int x8, MaskRow &out)
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

// The samples of pixel (fx, fy) inside the triangle across n.
void inside_across(const PartialAcross &n, const float *offset, int k, float fx, float fy, std::uint32_t &in_lo,
                   std::uint32_t &in_hi)
{
    in_lo = in_hi = 0;
    for (int j = 0; j < k; ++j) {
        const float v = fy + offset[j];
        for (int i = 0; i < k; ++i) {
            const float u = fx + offset[i];
            const bool in = n.ea[0] * u + n.eb[0] * v >= n.held[0] && n.ea[1] * u + n.eb[1] * v >= n.held[1];
            const int b = j * k + i;
            in_lo |= shift_left(std::uint32_t(in), b);
            in_hi |= shift_left(std::uint32_t(in), b >= 32 ? b - 32 : 32);
        }
    }
}

}  // namespace

unsigned merge_partial_rows_scalar(PartialRows &r, const RowsRuns &runs, int y_first, unsigned found,
                                   const PartialLayer &b)
{
    const int k = r.k;
    const unsigned row_lanes = (1u << k) - 1;
    const auto pixel_of = [&r](int column) { return int(std::uint64_t(column) * r.reciprocal >> 32); };
    int resume = r.resume_x8;
    r.resume_x8 = 0;
    for (; found; found &= found - 1, resume = 0) {
        const int row = __builtin_ctz(found), y = y_first + row, l = row * k;
        const float fy = float(y), depth_term = r.zb * fy + r.zc;
        const std::size_t row_tiles = std::size_t(y / tile_size) * std::size_t(b.tiles_x);
        const std::size_t row_offset = std::size_t(y % tile_size) * tile_size;
        const int skip0 = pixel_of(runs.whole_first[l] + k - 1) + 1, skip1 = pixel_of(runs.whole_last[l] + 1) - 2;
        unsigned band_edges = 0;
        for (int e = 0; e < 3; ++e)
            band_edges |= unsigned((runs.band_lanes[e] >> l & row_lanes) != 0) << e;
        const int last_pixel = pixel_of(runs.last[l]);
        for (int x8 = std::max(pixel_of(runs.first[l]) / tile_size * tile_size, resume); x8 <= last_pixel;
             x8 += tile_size) {
            if (x8 >= skip0 && x8 + tile_size - 1 <= skip1)
                continue;
            const std::size_t tile = row_tiles + std::size_t(x8 / tile_size);
            if ((!b.dirty[tile] && b.tile_max[tile] < r.behind) || b.farthest_bound[tile] < r.behind)
                continue;
            const std::size_t index = tile * tile_pixels + row_offset;
            float *const depth = b.depth + index;
            float z[tile_size];
            unsigned farther = 0;
            for (int lane = 0; lane < tile_size; ++lane) {
                z[lane] = widened(std::min(r.za * float(x8 + lane) + depth_term, r.zcap), r.depth_error);
                farther |= unsigned(z[lane] < depth[lane]) << lane;
            }
            if (!farther)
                continue;
            MaskRow mask, band;
            unsigned taking = run_masks(runs.held_lo + l, runs.held_hi + l, k, x8, mask) & farther;
            for (int e = 0; e < 3; ++e) {
                if (!(band_edges >> e & 1))
                    continue;
                const unsigned lanes = run_masks(runs.band_lo[e] + l, runs.band_hi[e] + l, k, x8, band) & farther;
                if (lanes && !(r.asked >> e & 1)) {
                    r.wanted = e;
                    r.resume_x8 = x8;
                    return found;
                }
                const PartialAcross *n = lanes ? r.across[e] : nullptr;
                if (!n)
                    continue;
                taking |= lanes;
                // Within the band beyond a shared edge, inside the triangle
                // across: held, at the farther of the two triangles' depths.
                const PolygonSetup &d = n->depth;
                for (int lane = 0; lane < tile_size; ++lane) {
                    const float fx = float(x8 + lane);
                    std::uint32_t in_lo, in_hi;
                    inside_across(*n, r.offset, k, fx, fy, in_lo, in_hi);
                    in_lo &= band.lo[lane];
                    in_hi &= band.hi[lane];
                    mask.lo[lane] |= in_lo;
                    mask.hi[lane] |= in_hi;
                    const float across_z = widened(std::min(d.za * fx + (d.zb * fy + d.zc), d.zcap), n->depth_error);
                    z[lane] = (in_lo | in_hi) != 0 ? std::max(z[lane], across_z) : z[lane];
                }
            }
            if (!taking)
                continue;
            std::uint32_t *const mask_lo = b.mask_lo + index, *const mask_hi = b.mask_hi + index;
            float *const partial_depth = b.partial_depth + index;
            for (int lane = 0; lane < tile_size; ++lane) {
                std::uint32_t lo = mask.lo[lane], hi = mask.hi[lane];
                if (!((lo | hi) != 0 && z[lane] < depth[lane]))
                    continue;
                const std::uint32_t old_lo = mask_lo[lane], old_hi = mask_hi[lane];
                const float farthest = (old_lo | old_hi) != 0 ? std::max(partial_depth[lane], z[lane]) : z[lane];
                lo |= old_lo;
                hi |= old_hi;
                if (lo != r.full_lo || hi != r.full_hi) {
                    mask_lo[lane] = lo;
                    mask_hi[lane] = hi;
                    partial_depth[lane] = farthest;
                    b.partial_written[tile] = 1;
                    continue;
                }
                // Every sample is held no farther than `farthest`; the layer
                // starts again empty, whether or not it was nearer.
                mask_lo[lane] = mask_hi[lane] = 0;
                if (farthest < depth[lane]) {
                    depth[lane] = farthest;
                    b.dirty[tile] = 1;
                    r.wrote = true;
                }
            }
        }
    }
    return 0;
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
