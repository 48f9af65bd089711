// SPDX-License-Identifier: MIT
// The AVX2 loops: eight depth pixels of a tile row, or eight tiles of a
// band, at once, the scalar loops' expressions lane by lane
// (raster_kernels_scalar.cpp); and the triangles' screen and setup, eight
// triangles at once, DepthRasterizer::polygon's and rasterize's.
#include "raster/raster_kernels.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>

namespace occu::raster {

namespace {

// A partly covered tile's rows band.row0 .. band.row1 - 1 (r from y8),
// tested against the N edges (N = 0: n edges) listed in `edge` (ea[edge[j]]
// and the row terms edge_rows[edge[j]]), their depth written where inside
// and nearer. Returns the lanes written, or'd over the rows.
template <int N>
inline __m256 fill_part_tile(float *tile, int row0, int row1, int y8, __m256 fx, __m256 z_column, __m256 zcap,
                             const __m256 *ea, const float (*edge_rows)[tile_size], const float *depth_rows,
                             const int *edge, int n)
{
    const int count = N > 0 ? N : n;
    const __m256 zero = _mm256_setzero_ps();
    __m256 a[N > 0 ? N : max_edges];
    const float *rows[N > 0 ? N : max_edges];
    for (int j = 0; j < count; ++j) {
        a[j] = _mm256_mul_ps(ea[edge[j]], fx);
        rows[j] = edge_rows[edge[j]];
    }
    __m256 wrote = zero;
    for (int y = row0; y < row1; ++y) {
        const int r = y - y8;
        __m256 inside;
        int j = 0;
        if constexpr (N > 0)
            inside = _mm256_cmp_ps(_mm256_add_ps(a[j++], _mm256_broadcast_ss(rows[0] + r)), zero, _CMP_GE_OQ);
        else
            inside = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
        for (; j < count; ++j)
            inside = _mm256_and_ps(inside,
                                   _mm256_cmp_ps(_mm256_add_ps(a[j], _mm256_broadcast_ss(rows[j] + r)), zero, _CMP_GE_OQ));
        if (_mm256_movemask_ps(inside) == 0)
            continue;
        const __m256 z = _mm256_min_ps(zcap, _mm256_add_ps(z_column, _mm256_broadcast_ss(depth_rows + r)));
        float *row = tile + r * tile_size;
        const __m256 old = _mm256_loadu_ps(row);
        const __m256 write = _mm256_and_ps(inside, _mm256_cmp_ps(z, old, _CMP_LT_OQ));
        _mm256_storeu_ps(row, _mm256_blendv_ps(old, z, write));
        wrote = _mm256_or_ps(wrote, write);
    }
    return wrote;
}

// band_terms for a triangle, its three edges and the depth in the four
// lanes of one vector: the same products and sums, each lane's row chosen
// by the same comparison (false for NaN: the last row).
inline void band_terms_triangle(const PolygonSetup &s, int row0, int row1, Band *band)
{
    band->y8 = row0 / tile_size * tile_size;
    band->row0 = row0;
    band->row1 = row1;
    const __m128 first = _mm_set1_ps(float(row0)), last = _mm_set1_ps(float(row1 - 1));
    const __m128 b = _mm_setr_ps(s.eb[0], s.eb[1], s.eb[2], s.zb), c = _mm_setr_ps(s.ec[0], s.ec[1], s.ec[2], s.zc);
    const __m128 rising = _mm_cmpgt_ps(b, _mm_setzero_ps());
    const __m128 least = _mm_add_ps(_mm_mul_ps(b, _mm_blendv_ps(last, first, rising)), c);
    const __m128 largest = _mm_add_ps(_mm_mul_ps(b, _mm_blendv_ps(first, last, rising)), c);
    alignas(16) float out[8];
    _mm_store_ps(out, least);
    _mm_store_ps(out + 4, largest);
    for (int e = 0; e < 3; ++e) {
        band->least_edge_term[e] = out[e];
        band->largest_edge_term[e] = out[4 + e];
    }
    band->nearest_depth_term = out[3];
    band->farthest_depth_term = out[7];
}

// fill_avx2 for polygons of `Edges` edges, or of s.edges for 0: triangles,
// most of the polygons, get their edge loops unrolled.
template <int Edges>
void fill_polygon(const PolygonSetup &s, const TileBuffer &buffer)
{
    const int edges = Edges > 0 ? Edges : s.edges;
    const __m256 lanes = _mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256 eights = _mm256_mul_ps(lanes, _mm256_set1_ps(float(tile_size)));
    const __m256 last_column = _mm256_set1_ps(float(tile_size - 1));
    const __m256 zero = _mm256_setzero_ps();
    const __m256 za = _mm256_set1_ps(s.za), zcap = _mm256_set1_ps(s.zcap);
    __m256 ea[max_edges], eb[max_edges], ec[max_edges];
    bool rising[max_edges];
    for (int e = 0; e < edges; ++e) {
        ea[e] = _mm256_set1_ps(s.ea[e]);
        eb[e] = _mm256_set1_ps(s.eb[e]);
        ec[e] = _mm256_set1_ps(s.ec[e]);
        rising[e] = s.ea[e] > 0.0f;
    }
    const bool depth_rising = s.za > 0.0f;
    Band band;
    alignas(32) float edge_rows[max_edges][tile_size], depth_rows[tile_size];
    for (int y8 = s.y0 / tile_size * tile_size; y8 < s.y1; y8 += tile_size) {
        if constexpr (Edges == 3)
            band_terms_triangle(s, y8 > s.y0 ? y8 : s.y0, y8 + tile_size < s.y1 ? y8 + tile_size : s.y1, &band);
        else
            band_terms(s, edges, y8 > s.y0 ? y8 : s.y0, y8 + tile_size < s.y1 ? y8 + tile_size : s.y1, &band);
        const bool all_rows = band.row0 == y8 && band.row1 == y8 + tile_size;
        // The row terms of the band's eight rows, eb Y + ec lane by lane,
        // once the band has a tile to fill.
        bool rows_ready = false;
        const std::size_t band_tiles = std::size_t(y8 / tile_size) * std::size_t(buffer.tiles_x);
        // Eight tiles of the band at once: tile_cover, tile_nearest_depth
        // and the bound test in lanes.
        for (int x_first = s.x0 / tile_size * tile_size; x_first < s.x1; x_first += tile_size * 8) {
            const int tiles_left = (s.x1 - x_first + tile_size - 1) / tile_size;
            const int tiles = tiles_left < 8 ? tiles_left : 8;
            const __m256 left = _mm256_add_ps(_mm256_set1_ps(float(x_first)), eights);
            const __m256 right = _mm256_add_ps(left, last_column);
            __m256 none = zero, whole = _mm256_cmp_ps(zero, zero, _CMP_EQ_OQ);
            // Per edge, the tiles wholly inside it (bit i for tile i), whose
            // pixels need no test against it.
            int edge_inside[Edges > 0 ? Edges : max_edges];
            for (int e = 0; e < edges; ++e) {
                const __m256 largest = _mm256_add_ps(_mm256_mul_ps(ea[e], rising[e] ? right : left),
                                                     _mm256_set1_ps(band.largest_edge_term[e]));
                none = _mm256_or_ps(none, _mm256_cmp_ps(largest, zero, _CMP_LT_OQ));
                const __m256 least = _mm256_add_ps(_mm256_mul_ps(ea[e], rising[e] ? left : right),
                                                   _mm256_set1_ps(band.least_edge_term[e]));
                const __m256 inside = _mm256_cmp_ps(least, zero, _CMP_GE_OQ);
                whole = _mm256_and_ps(whole, inside);
                edge_inside[e] = _mm256_movemask_ps(inside);
            }
            const int in_band = (1 << tiles) - 1;
            int fill = ~_mm256_movemask_ps(none) & in_band;
            if (fill == 0)
                continue;
            const std::size_t first_tile = band_tiles + std::size_t(x_first / tile_size);
            const __m256 nearest = _mm256_min_ps(zcap, _mm256_add_ps(_mm256_mul_ps(za, depth_rising ? left : right),
                                                                     _mm256_set1_ps(band.nearest_depth_term)));
            const __m256i load =
                _mm256_cmpgt_epi32(_mm256_set1_epi32(tiles), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
            const __m256 bound = _mm256_maskload_ps(buffer.farthest_bound + first_tile, load);
            fill &= ~_mm256_movemask_ps(_mm256_cmp_ps(nearest, bound, _CMP_GE_OQ));
            if (fill == 0)
                continue;
            const int whole_tiles = _mm256_movemask_ps(whole);
            if (!rows_ready) {
                const __m256 fy = _mm256_add_ps(_mm256_set1_ps(float(y8)), lanes);
                for (int e = 0; e < edges; ++e)
                    _mm256_store_ps(edge_rows[e], _mm256_add_ps(_mm256_mul_ps(eb[e], fy), ec[e]));
                _mm256_store_ps(depth_rows,
                                _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(s.zb), fy), _mm256_set1_ps(s.zc)));
                rows_ready = true;
            }
            for (; fill != 0; fill &= fill - 1) {
                const int i = __builtin_ctz(unsigned(fill));
                const int x8 = x_first + i * tile_size;
                const std::size_t t = first_tile + std::size_t(i);
                float *tile = tile_at(buffer, t);
                // float(x8 + lane), exactly, as the scalar loop converts it.
                const __m256 fx = _mm256_add_ps(_mm256_set1_ps(float(x8)), lanes);
                const __m256 z_column = _mm256_mul_ps(za, fx);
                if (whole_tiles >> i & 1) {
                    // std::min(z, zcap) is (zcap < z ? zcap : z), which
                    // min_ps(zcap, z) is; keeping z where z < old is min_ps(z, old).
                    for (int y = band.row0; y < band.row1; ++y) {
                        float *row = tile + (y - y8) * tile_size;
                        const __m256 z =
                            _mm256_min_ps(zcap, _mm256_add_ps(z_column, _mm256_broadcast_ss(depth_rows + (y - y8))));
                        _mm256_storeu_ps(row, _mm256_min_ps(z, _mm256_loadu_ps(row)));
                    }
                    buffer.dirty[t] = 1;
                    if (all_rows) {
                        // Every pixel is now no farther than the polygon's farthest here.
                        const float farthest = tile_farthest_depth(s, band, x8);
                        if (farthest < buffer.farthest_bound[t])
                            buffer.farthest_bound[t] = farthest;
                    }
                    continue;
                }
                __m256 wrote = zero;
                // Only the edges the tile is not wholly inside: an edge's
                // value at a pixel is no less than its least over the tile
                // (the corner test above: the same products and sum at the
                // tile's corner, and float rounding is monotone), so where
                // that is >= 0 the pixel's own test passes too.
                int edge[Edges > 0 ? Edges : max_edges], crossing = 0;
                for (int e = 0; e < edges; ++e)
                    if (!(edge_inside[e] >> i & 1))
                        edge[crossing++] = e;
                if (crossing == 1)
                    wrote = fill_part_tile<1>(tile, band.row0, band.row1, y8, fx, z_column, zcap, ea, edge_rows,
                                              depth_rows, edge, 1);
                else if (crossing == 2)
                    wrote = fill_part_tile<2>(tile, band.row0, band.row1, y8, fx, z_column, zcap, ea, edge_rows,
                                              depth_rows, edge, 2);
                else if (Edges > 0)
                    wrote = fill_part_tile<Edges>(tile, band.row0, band.row1, y8, fx, z_column, zcap, ea, edge_rows,
                                                  depth_rows, edge, crossing);
                else
                    wrote = fill_part_tile<0>(tile, band.row0, band.row1, y8, fx, z_column, zcap, ea, edge_rows,
                                              depth_rows, edge, crossing);
                if (_mm256_movemask_ps(wrote) != 0)
                    buffer.dirty[t] = 1;
            }
        }
    }
}

}  // namespace

void fill_avx2(const PolygonSetup &s, const TileBuffer &buffer)
{
    if (s.edges == 3)
        fill_polygon<3>(s, buffer);
    else
        fill_polygon<0>(s, buffer);
}

namespace {

// Constants of partial_rows_runs_avx2's crossings.
struct CrossingConstants {
    __m256d eight_eps, four_eps, one, zero, half, k, sign, lo, hi, none_rising, none_falling;
};

// One line's columns in four lanes of sample rows v, given its slope times
// v (bv, shared by an edge's held line and its reach: the same slope) and
// that product's magnitude: line_column's expressions
// (raster_kernels_scalar.cpp) for the line's kind alone.
inline __m128i line_columns(const Crossings &c, int line, __m256d bv, __m256d bv_size, const CrossingConstants &x)
{
    const __m256d start = _mm256_set1_pd(c.start[line]);
    const __m256d crossing = _mm256_add_pd(start, bv);
    const __m256d terms = _mm256_add_pd(_mm256_andnot_pd(x.sign, start), bv_size);
    if (c.level[line]) {
        // The whole row or none.
        const __m256d holds =
            _mm256_cmp_pd(_mm256_sub_pd(crossing, _mm256_mul_pd(x.eight_eps, terms)), x.zero, _CMP_GE_OQ);
        return _mm256_cvtpd_epi32(_mm256_blendv_pd(x.none_rising, x.lo, holds));
    }
    const __m256d slack = _mm256_mul_pd(x.eight_eps, _mm256_add_pd(terms, _mm256_andnot_pd(x.sign, crossing)));
    if (c.rising[line]) {
        // The first column from (crossing + slack) k - 0.5 up; first <=
        // c_hi (false for NaN) ? max(first, c_lo) : c_hi + 1, as the
        // scalar (first < c_lo ? c_lo : first; max_pd gives c_lo where
        // first is NaN, which the compare then drops).
        const __m256d x_up = _mm256_sub_pd(_mm256_mul_pd(_mm256_add_pd(crossing, slack), x.k), x.half);
        const __m256d first = _mm256_round_pd(
            _mm256_add_pd(x_up, _mm256_mul_pd(x.four_eps, _mm256_add_pd(_mm256_andnot_pd(x.sign, x_up), x.one))),
            _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC);
        return _mm256_cvtpd_epi32(
            _mm256_blendv_pd(x.none_rising, _mm256_max_pd(first, x.lo), _mm256_cmp_pd(first, x.hi, _CMP_LE_OQ)));
    }
    // The last column from (crossing - slack) k - 0.5 down.
    const __m256d x_down = _mm256_sub_pd(_mm256_mul_pd(_mm256_sub_pd(crossing, slack), x.k), x.half);
    const __m256d last = _mm256_round_pd(
        _mm256_sub_pd(x_down, _mm256_mul_pd(x.four_eps, _mm256_add_pd(_mm256_andnot_pd(x.sign, x_down), x.one))),
        _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    return _mm256_cvtpd_epi32(
        _mm256_blendv_pd(x.none_falling, _mm256_min_pd(last, x.hi), _mm256_cmp_pd(last, x.lo, _CMP_GE_OQ)));
}

// Per divisor k, the permutations that bring each row's k lanes together:
// after v = op(v, permute(v, p)) for each of the first steps, the lane of
// a row's first sample row holds the op over its k lanes (the lanes that
// hold nothing made neutral first).
struct RowReduction {
    int steps;
    std::int32_t permute[3][8];
};
constexpr RowReduction row_reduction[9] = {
    {0, {}},
    {0, {}},
    {1, {{1, 0, 3, 2, 5, 4, 7, 6}}},
    {2, {{1, 2, 0, 4, 5, 3, 6, 7}, {1, 2, 0, 4, 5, 3, 6, 7}}},
    {2, {{1, 0, 3, 2, 5, 4, 7, 6}, {2, 3, 0, 1, 6, 7, 4, 5}}},
    {3, {{1, 0, 3, 2, 5, 4, 7, 6}, {2, 3, 0, 1, 6, 7, 4, 5}, {4, 5, 6, 7, 0, 1, 2, 3}}},
    {3, {{1, 0, 3, 2, 5, 4, 7, 6}, {2, 3, 0, 1, 6, 7, 4, 5}, {4, 5, 6, 7, 0, 1, 2, 3}}},
    {3, {{1, 0, 3, 2, 5, 4, 7, 6}, {2, 3, 0, 1, 6, 7, 4, 5}, {4, 5, 6, 7, 0, 1, 2, 3}}},
    {3, {{1, 0, 3, 2, 5, 4, 7, 6}, {2, 3, 0, 1, 6, 7, 4, 5}, {4, 5, 6, 7, 0, 1, 2, 3}}},
};

// partial_rows_runs_avx2 for a polygon of Edges edges (0: any count) whose
// rows in this call lie in the low four lanes (High false: lanes 4-7 are
// not computed and hold nothing read) or reach lanes 4-7 (High true).
template <int Edges, bool High>
unsigned rows_runs(const Crossings &c, int y, int rows, RowsRuns &out)
{
    const int kk = c.k, edges = Edges ? Edges : c.edges;
    CrossingConstants x;
    x.eight_eps = _mm256_set1_pd(8.0 * 0x1p-52);
    x.four_eps = _mm256_set1_pd(4.0 * 0x1p-52);
    x.one = _mm256_set1_pd(1.0);
    x.zero = _mm256_setzero_pd();
    x.half = _mm256_set1_pd(0.5);
    x.k = _mm256_set1_pd(double(kk));
    x.sign = _mm256_set1_pd(-0.0);
    x.lo = _mm256_set1_pd(double(c.c_lo));
    x.hi = _mm256_set1_pd(double(c.c_hi));
    x.none_rising = _mm256_set1_pd(double(c.c_hi + 1));
    x.none_falling = _mm256_set1_pd(double(c.c_lo - 1));
    // v = (y + l / k) + ((l mod k) + 0.5) / k: the row's y is exact in double.
    const __m256d row = _mm256_set1_pd(double(y));
    const __m256d v_low = _mm256_add_pd(_mm256_add_pd(row, _mm256_loadu_pd(c.lane_row)), _mm256_loadu_pd(c.lane_offset));
    const __m256d v_high =
        High ? _mm256_add_pd(_mm256_add_pd(row, _mm256_loadu_pd(c.lane_row + 4)), _mm256_loadu_pd(c.lane_offset + 4))
             : v_low;
    // Edge e's own column and, with a triangle across, its reach's; the
    // two lines share the slope, so slope v once for both.
    __m256i own[Edges ? Edges : max_edges], reach[3];
#pragma GCC unroll 3
    for (int e = 0; e < edges; ++e) {
        const __m256d slope = _mm256_set1_pd(c.slope[e]);
        const __m256d bv_low = _mm256_mul_pd(slope, v_low), size_low = _mm256_andnot_pd(x.sign, bv_low);
        const __m256d bv_high = High ? _mm256_mul_pd(slope, v_high) : bv_low;
        const __m256d size_high = High ? _mm256_andnot_pd(x.sign, bv_high) : size_low;
        const auto columns = [&](int line) {
            const __m128i low = line_columns(c, line, bv_low, size_low, x);
            return High ? _mm256_set_m128i(line_columns(c, line, bv_high, size_high, x), low)
                        : _mm256_castsi128_si256(low);
        };
        own[e] = columns(e);
        if (e < 3 && (c.candidates >> e & 1))
            reach[e] = columns(c.reach_line[e]);
    }
    const __m256i c_lo = _mm256_set1_epi32(c.c_lo), c_hi = _mm256_set1_epi32(c.c_hi);
    const __m256i ones = _mm256_set1_epi32(1);
    // The lanes that hold a sample row of the polygon's.
    const __m256i valid =
        _mm256_cmpgt_epi32(_mm256_set1_epi32(rows * kk), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    // Edge e's bound: from its column on where it rises (lower), else up
    // to it (upper).
    __m256i lower[Edges ? Edges : max_edges], upper[Edges ? Edges : max_edges];
    __m256i held_lo = c_lo, held_hi = c_hi;
#pragma GCC unroll 3
    for (int e = 0; e < edges; ++e) {
        const bool rises = c.rising_edges >> e & 1;
        lower[e] = rises ? own[e] : c_lo;
        upper[e] = rises ? c_hi : own[e];
        held_lo = _mm256_max_epi32(held_lo, lower[e]);
        held_hi = _mm256_min_epi32(held_hi, upper[e]);
    }
    _mm256_store_si256(reinterpret_cast<__m256i *>(out.held_lo), held_lo);
    _mm256_store_si256(reinterpret_cast<__m256i *>(out.held_hi), held_hi);
    // Columns of the nonempty runs: the least first and greatest last.
    const auto nonempty = [&](__m256i run_lo, __m256i run_hi) {
        return _mm256_andnot_si256(_mm256_cmpgt_epi32(run_lo, run_hi), valid);
    };
    const __m256i past = _mm256_set1_epi32(c.c_hi + 1), before = _mm256_set1_epi32(c.c_lo - 1);
    const __m256i some = nonempty(held_lo, held_hi);
    __m256i first = _mm256_blendv_epi8(past, held_lo, some), last = _mm256_blendv_epi8(before, held_hi, some);
    // Triangles only (c.edges == 3) have edges with a triangle across.
    for (int e = 0; e < 3; ++e) {
        out.band_lanes[e] = 0;
        if (!(c.candidates >> e & 1))
            continue;
        const bool rises = c.rising_edges >> e & 1;
        const int o1 = e == 2 ? 0 : e + 1, o2 = e == 0 ? 2 : e - 1;
        const __m256i band_lo =
            _mm256_max_epi32(_mm256_max_epi32(rises ? reach[e] : _mm256_add_epi32(own[e], ones), lower[o1]), lower[o2]);
        const __m256i band_hi =
            _mm256_min_epi32(_mm256_min_epi32(rises ? _mm256_sub_epi32(own[e], ones) : reach[e], upper[o1]), upper[o2]);
        _mm256_store_si256(reinterpret_cast<__m256i *>(out.band_lo[e]), band_lo);
        _mm256_store_si256(reinterpret_cast<__m256i *>(out.band_hi[e]), band_hi);
        const __m256i in_band = nonempty(band_lo, band_hi);
        out.band_lanes[e] = unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(in_band)));
        first = _mm256_blendv_epi8(first, _mm256_min_epi32(first, band_lo), in_band);
        last = _mm256_blendv_epi8(last, _mm256_max_epi32(last, band_hi), in_band);
    }
    // Per row, over its k lanes.
    __m256i whole_first = _mm256_blendv_epi8(c_lo, held_lo, valid);
    __m256i whole_last = _mm256_blendv_epi8(c_hi, held_hi, valid);
    const RowReduction &reduction = row_reduction[kk];
    for (int step = 0; step < reduction.steps; ++step) {
        const __m256i p = _mm256_loadu_si256(reinterpret_cast<const __m256i *>(reduction.permute[step]));
        first = _mm256_min_epi32(first, _mm256_permutevar8x32_epi32(first, p));
        last = _mm256_max_epi32(last, _mm256_permutevar8x32_epi32(last, p));
        whole_first = _mm256_max_epi32(whole_first, _mm256_permutevar8x32_epi32(whole_first, p));
        whole_last = _mm256_min_epi32(whole_last, _mm256_permutevar8x32_epi32(whole_last, p));
    }
    _mm256_store_si256(reinterpret_cast<__m256i *>(out.first), first);
    _mm256_store_si256(reinterpret_cast<__m256i *>(out.last), last);
    _mm256_store_si256(reinterpret_cast<__m256i *>(out.whole_first), whole_first);
    _mm256_store_si256(reinterpret_cast<__m256i *>(out.whole_last), whole_last);
    // Bit r: lane r k has first <= last.
    const unsigned lanes = unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(first, last)))) ^ 0xffu;
    unsigned found = 0;
    for (int r = 0; r < rows; ++r)
        found |= (lanes >> (r * kk) & 1u) << r;
    return found;
}

}  // namespace

unsigned partial_rows_runs_avx2(const Crossings &c, int y, RowsRuns &out)
{
    // Each line's crossings in one or two steps of four double lanes, the
    // scalar's expressions lane by lane, kept in registers (no store of
    // four columns read back as eight); none for lanes past the polygon's
    // last row.
    const int rows = std::min(rows_at_once(c.k), c.y_end - y);
    const bool high = rows * c.k > 4;
    if (c.edges == 3)
        return high ? rows_runs<3, true>(c, y, rows, out) : rows_runs<3, false>(c, y, rows, out);
    return high ? rows_runs<0, true>(c, y, rows, out) : rows_runs<0, false>(c, y, rows, out);
}

namespace {

// partial_next_up lane by lane: the next float up, a NaN or +infinity kept.
inline __m256 next_up(__m256 z)
{
    z = _mm256_add_ps(z, _mm256_setzero_ps());
    const __m256i bits = _mm256_castps_si256(z);
    // -1 below zero, else +1.
    const __m256i step =
        _mm256_or_si256(_mm256_castps_si256(_mm256_cmp_ps(z, _mm256_setzero_ps(), _CMP_LT_OQ)), _mm256_set1_epi32(1));
    const __m256 keep = _mm256_or_ps(_mm256_cmp_ps(z, z, _CMP_UNORD_Q),
                                     _mm256_cmp_ps(z, _mm256_set1_ps(__builtin_inff()), _CMP_EQ_OQ));
    return _mm256_blendv_ps(_mm256_castsi256_ps(_mm256_add_epi32(bits, step)), z, keep);
}

// partial_next_up(float(double(z) + error)) lane by lane.
inline __m256 widened(__m256 z, double error)
{
    const __m256d e = _mm256_set1_pd(error);
    const __m128 low = _mm256_cvtpd_ps(_mm256_add_pd(_mm256_cvtps_pd(_mm256_castps256_ps128(z)), e));
    const __m128 high = _mm256_cvtpd_ps(_mm256_add_pd(_mm256_cvtps_pd(_mm256_extractf128_ps(z, 1)), e));
    return next_up(_mm256_insertf128_ps(_mm256_castps128_ps256(low), high, 1));
}

}  // namespace

namespace {

// The runs lo[j] .. hi[j] of sample rows j < K in depth pixels x8 .. x8 +
// 7 (first: each lane's first sample column, x8 K + lane K) as their
// masks, the scalar loop's expressions (shifts by 32 or more give 0 in
// both); the shifts into place are constants, and the high plane is 0
// where K K <= 32.
template <int K>
inline void run_masks(const std::int32_t *run_lo, const std::int32_t *run_hi, __m256i first, __m256i &lo, __m256i &hi)
{
    const __m256i zero = _mm256_setzero_si256(), kk = _mm256_set1_epi32(K), one = _mm256_set1_epi32(1);
    lo = hi = zero;
    for (int j = 0; j < K; ++j) {
        const __m256i s = _mm256_min_epi32(_mm256_max_epi32(_mm256_sub_epi32(_mm256_set1_epi32(run_lo[j]), first), zero), kk);
        const __m256i t =
            _mm256_min_epi32(_mm256_max_epi32(_mm256_sub_epi32(_mm256_set1_epi32(run_hi[j] + 1), first), s), kk);
        const __m256i bits = _mm256_sub_epi32(_mm256_sllv_epi32(one, t), _mm256_sllv_epi32(one, s));
        const int b = j * K;
        if (b < 32)
            lo = _mm256_or_si256(lo, _mm256_slli_epi32(bits, b));
        if (b >= 32)
            hi = _mm256_or_si256(hi, _mm256_slli_epi32(bits, b - 32));
        else if (b + K > 32)
            hi = _mm256_or_si256(hi, _mm256_srli_epi32(bits, 32 - b));
    }
}

// The lanes with a sample (bit l: lane l).
inline unsigned lanes_holding(__m256i lo, __m256i hi)
{
    return unsigned(~_mm256_movemask_ps(
               _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_or_si256(lo, hi), _mm256_setzero_si256())))) &
           0xffu;
}

// The depth pixel of sample column c, c / K, lane by lane, for 0 <= c <
// 2^20 K: a shift for K a power of two; else the float quotient truncated.
// c and K are exact floats, and c / K lies at least 1 / K >= 1 / 8 below
// the next integer (or is one), farther than the quotient's rounding (half
// an ulp, at most 2^-4 below 2^20), so it truncates to the integer below.
template <int K>
inline __m256i pixels_of(__m256i column)
{
    if constexpr ((K & (K - 1)) == 0)
        return _mm256_srli_epi32(column, __builtin_ctz(unsigned(K)));
    else
        return _mm256_cvttps_epi32(_mm256_div_ps(_mm256_cvtepi32_ps(column), _mm256_set1_ps(float(K))));
}

// The bounds of each row's walk (the scalar loop's, per row), for all of
// a call's rows at once in the lanes of its first sample row (lane r K of
// the runs' row arrays, which hold columns in [-1, K (width + 1)]): the
// first tile row, the last pixel, the whole pixels' tile rows passed over
// (skip0 .. skip1), and bit e for each edge whose band holds a sample in
// one of the row's K lanes. The other lanes hold nothing read.
struct RowBounds {
    alignas(32) std::int32_t start[8], last_pixel[8], skip0[8], skip1[8], band_edges[8];
};

template <int K>
inline void row_bounds(const RowsRuns &runs, RowBounds &out)
{
    const auto load = [](const std::int32_t *v) { return _mm256_load_si256(reinterpret_cast<const __m256i *>(v)); };
    const auto store = [](std::int32_t *v, __m256i x) { _mm256_store_si256(reinterpret_cast<__m256i *>(v), x); };
    const __m256i one = _mm256_set1_epi32(1);
    store(out.start, _mm256_andnot_si256(_mm256_set1_epi32(tile_size - 1), pixels_of<K>(load(runs.first))));
    store(out.last_pixel, pixels_of<K>(load(runs.last)));
    store(out.skip0, _mm256_add_epi32(pixels_of<K>(_mm256_add_epi32(load(runs.whole_first), _mm256_set1_epi32(K - 1))), one));
    store(out.skip1, _mm256_sub_epi32(pixels_of<K>(_mm256_add_epi32(load(runs.whole_last), one)), _mm256_set1_epi32(2)));
    // Lane l: bit e where band_lanes[e] >> l & (2^K - 1) is not 0.
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), row_lanes = _mm256_set1_epi32((1 << K) - 1);
    __m256i edges = _mm256_setzero_si256();
    for (int e = 0; e < 3; ++e) {
        const __m256i in_row = _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(runs.band_lanes[e])), lane), row_lanes);
        edges = _mm256_or_si256(edges, _mm256_andnot_si256(_mm256_cmpeq_epi32(in_row, _mm256_setzero_si256()),
                                                           _mm256_set1_epi32(1 << e)));
    }
    store(out.band_edges, edges);
}

// merge_partial_rows_avx2 for divisor K, its sample loops unrolled.
template <int K>
__attribute__((always_inline)) inline unsigned merge_rows_k(PartialRows &r, const RowsRuns &runs, int y_first,
                                                          unsigned found, const PartialLayer &b)
{
    constexpr int k = K;
    RowBounds bounds;
    row_bounds<K>(runs, bounds);
    const __m256i zero = _mm256_setzero_si256(), ones = _mm256_set1_epi32(-1);
    const __m256i lane_columns = _mm256_setr_epi32(0, k, 2 * k, 3 * k, 4 * k, 5 * k, 6 * k, 7 * k);
    const __m256 lane_x = _mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256 za = _mm256_set1_ps(r.za), zcap = _mm256_set1_ps(r.zcap);
    const __m256i full_lo = _mm256_set1_epi32(int(r.full_lo)), full_hi = _mm256_set1_epi32(int(r.full_hi));
    const PartialDepthStep step = r.depth_step;
    const __m256 step_add = _mm256_set1_ps(step.add), step_lo = _mm256_set1_ps(step.lo), step_hi = _mm256_set1_ps(step.hi);
    int resume = r.resume_x8;
    r.resume_x8 = 0;
    for (; found; found &= found - 1, resume = 0) {
        const int row = __builtin_ctz(found), y = y_first + row, l = row * k;
        const float fy = float(y);
        const __m256 depth_term = _mm256_set1_ps(r.zb * fy + r.zc);
        // y >= 0: its tile row and row within the tile by shifts.
        const std::size_t row_tiles = std::size_t(unsigned(y) / tile_size) * std::size_t(b.tiles_x);
        const std::size_t row_offset = std::size_t(unsigned(y) % tile_size) * tile_size;
        const int skip0 = bounds.skip0[l], skip1 = bounds.skip1[l], last_pixel = bounds.last_pixel[l];
        const unsigned band_edges = unsigned(bounds.band_edges[l]);
        const int start = bounds.start[l];
        for (int x8 = start > resume ? start : resume; x8 <= last_pixel; x8 += tile_size) {
            if (x8 >= skip0 && x8 + tile_size - 1 <= skip1) {
                // On to the last tile row passed over.
                x8 += int(unsigned(skip1 - (tile_size - 1) - x8) / tile_size * tile_size);
                continue;
            }
            // x8 >= 0: its tile by a shift.
            const std::size_t tile = row_tiles + std::size_t(unsigned(x8) / tile_size);
            if ((!b.dirty[tile] && b.tile_max[tile] < r.behind) || b.farthest_bound[tile] < r.behind)
                continue;
            const std::size_t index = tile * tile_pixels + row_offset;
            // float(x8 + lane), exactly, as the scalar loop converts it;
            // std::min(z, zcap) is min_ps(zcap, z); std::max(a, b) is
            // max_ps(b, a).
            const __m256 fx = _mm256_add_ps(_mm256_set1_ps(float(x8)), lane_x);
            // The depth bound: one float sum where every lane lies in the
            // step's range (most tile rows), else through double.
            const __m256 plane = _mm256_min_ps(zcap, _mm256_add_ps(_mm256_mul_ps(za, fx), depth_term));
            const __m256 in_step =
                _mm256_and_ps(_mm256_cmp_ps(plane, step_lo, _CMP_GE_OQ), _mm256_cmp_ps(plane, step_hi, _CMP_LE_OQ));
            __m256 z = _mm256_movemask_ps(in_step) == 0xff ? _mm256_add_ps(plane, step_add) : widened(plane, r.depth_error);
            const __m256 depth = _mm256_loadu_ps(b.depth + index);
            const unsigned farther = unsigned(_mm256_movemask_ps(_mm256_cmp_ps(z, depth, _CMP_LT_OQ)));
            if (!farther)
                continue;
            const __m256i first = _mm256_add_epi32(_mm256_set1_epi32(x8 * k), lane_columns);
            __m256i lo, hi;
            run_masks<K>(runs.held_lo + l, runs.held_hi + l, first, lo, hi);
            unsigned taking = lanes_holding(lo, hi) & farther;
            for (unsigned edges = band_edges; edges; edges &= edges - 1) {
                const int e = __builtin_ctz(edges);
                __m256i band_lo, band_hi;
                run_masks<K>(runs.band_lo[e] + l, runs.band_hi[e] + l, first, band_lo, band_hi);
                const unsigned lanes = lanes_holding(band_lo, band_hi) & farther;
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
                const __m256 ea0 = _mm256_set1_ps(n->ea[0]), ea1 = _mm256_set1_ps(n->ea[1]);
                const __m256 held0 = _mm256_set1_ps(n->held[0]), held1 = _mm256_set1_ps(n->held[1]);
                __m256i in_lo = zero, in_hi = zero;
                for (int j = 0; j < k; ++j) {
                    const float v = fy + r.offset[j];
                    const __m256 bv0 = _mm256_set1_ps(n->eb[0] * v), bv1 = _mm256_set1_ps(n->eb[1] * v);
                    for (int i = 0; i < k; ++i) {
                        const __m256 u = _mm256_add_ps(fx, _mm256_set1_ps(r.offset[i]));
                        const __m256 in = _mm256_and_ps(
                            _mm256_cmp_ps(_mm256_add_ps(_mm256_mul_ps(ea0, u), bv0), held0, _CMP_GE_OQ),
                            _mm256_cmp_ps(_mm256_add_ps(_mm256_mul_ps(ea1, u), bv1), held1, _CMP_GE_OQ));
                        const int bit = j * k + i;
                        if (bit < 32)
                            in_lo = _mm256_or_si256(
                                in_lo, _mm256_and_si256(_mm256_castps_si256(in), _mm256_set1_epi32(int(1u << bit))));
                        else
                            in_hi = _mm256_or_si256(in_hi, _mm256_and_si256(_mm256_castps_si256(in),
                                                                            _mm256_set1_epi32(int(1u << (bit - 32)))));
                    }
                }
                in_lo = _mm256_and_si256(in_lo, band_lo);
                in_hi = _mm256_and_si256(in_hi, band_hi);
                lo = _mm256_or_si256(lo, in_lo);
                hi = _mm256_or_si256(hi, in_hi);
                const PolygonSetup &d = n->depth;
                const __m256 across_z = widened(
                    _mm256_min_ps(_mm256_set1_ps(d.zcap), _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(d.za), fx),
                                                                        _mm256_set1_ps(d.zb * fy + d.zc))),
                    n->depth_error);
                const __m256 some =
                    _mm256_castsi256_ps(_mm256_xor_si256(_mm256_cmpeq_epi32(_mm256_or_si256(in_lo, in_hi), zero), ones));
                z = _mm256_blendv_ps(z, _mm256_max_ps(across_z, z), some);
            }
            if (!taking)
                continue;
            const __m256i held_none = _mm256_cmpeq_epi32(_mm256_or_si256(lo, hi), zero);
            const __m256 take = _mm256_andnot_ps(_mm256_castsi256_ps(held_none), _mm256_cmp_ps(z, depth, _CMP_LT_OQ));
            if (_mm256_movemask_ps(take) == 0)
                continue;
            std::uint32_t *const mask_lo = b.mask_lo + index, *const mask_hi = b.mask_hi + index;
            float *const partial_depth = b.partial_depth + index;
            const __m256i old_lo = _mm256_loadu_si256(reinterpret_cast<const __m256i *>(mask_lo));
            const __m256i old_hi = _mm256_loadu_si256(reinterpret_cast<const __m256i *>(mask_hi));
            const __m256 old_depth = _mm256_loadu_ps(partial_depth);
            const __m256 open =
                _mm256_castsi256_ps(_mm256_xor_si256(_mm256_cmpeq_epi32(_mm256_or_si256(old_lo, old_hi), zero), ones));
            const __m256 farthest = _mm256_blendv_ps(z, _mm256_max_ps(z, old_depth), open);
            lo = _mm256_or_si256(lo, old_lo);
            hi = _mm256_or_si256(hi, old_hi);
            const __m256 full = _mm256_castsi256_ps(
                _mm256_and_si256(_mm256_cmpeq_epi32(lo, full_lo), _mm256_cmpeq_epi32(hi, full_hi)));
            // Taken and not full: the joint mask and the farther depth
            // stored. Taken and full: the mask empties, and the depth is
            // kept where nearer.
            const __m256 store = _mm256_andnot_ps(full, take), fills = _mm256_and_ps(full, take);
            const __m256 nearer = _mm256_and_ps(fills, _mm256_cmp_ps(farthest, depth, _CMP_LT_OQ));
            const __m256i stored_lo = _mm256_andnot_si256(_mm256_castps_si256(full), lo);
            const __m256i stored_hi = _mm256_andnot_si256(_mm256_castps_si256(full), hi);
            _mm256_storeu_si256(reinterpret_cast<__m256i *>(mask_lo),
                                _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(old_lo),
                                                                     _mm256_castsi256_ps(stored_lo), take)));
            _mm256_storeu_si256(reinterpret_cast<__m256i *>(mask_hi),
                                _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(old_hi),
                                                                     _mm256_castsi256_ps(stored_hi), take)));
            _mm256_storeu_ps(partial_depth, _mm256_blendv_ps(old_depth, farthest, store));
            _mm256_storeu_ps(b.depth + index, _mm256_blendv_ps(depth, farthest, nearer));
            if (_mm256_movemask_ps(nearer) != 0) {
                b.dirty[tile] = 1;
                r.wrote = true;
            }
            if (_mm256_movemask_ps(store) != 0)
                b.partial_written[tile] = 1;
        }
    }
    return 0;
}

}  // namespace

unsigned merge_partial_rows_avx2(PartialRows &r, const RowsRuns &runs, int y, unsigned found, const PartialLayer &b)
{
    switch (r.k) {
    case 1: return merge_rows_k<1>(r, runs, y, found, b);
    case 2: return merge_rows_k<2>(r, runs, y, found, b);
    case 3: return merge_rows_k<3>(r, runs, y, found, b);
    case 4: return merge_rows_k<4>(r, runs, y, found, b);
    case 5: return merge_rows_k<5>(r, runs, y, found, b);
    case 6: return merge_rows_k<6>(r, runs, y, found, b);
    case 7: return merge_rows_k<7>(r, runs, y, found, b);
    default: return merge_rows_k<8>(r, runs, y, found, b);
    }
}

bool tile_behind_avx2(const float *tile, int c0, int c1, int r0, int r1, float z)
{
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256 columns = _mm256_castsi256_ps(_mm256_and_si256(_mm256_cmpgt_epi32(lane, _mm256_set1_epi32(c0 - 1)),
                                                                _mm256_cmpgt_epi32(_mm256_set1_epi32(c1), lane)));
    const __m256 zz = _mm256_set1_ps(z);
    for (int r = r0; r < r1; ++r) {
        // A pixel not nearer than z (or NaN) in a chosen column: visible.
        const __m256 not_behind = _mm256_cmp_ps(_mm256_loadu_ps(tile + r * tile_size), zz, _CMP_NLT_UQ);
        if (_mm256_movemask_ps(_mm256_and_ps(not_behind, columns)) != 0)
            return false;
    }
    return true;
}

}  // namespace occu::raster

namespace occu::raster {

namespace {

struct ClipVertex {
    __m256 x, y, z, w;
    __m256 px, py, pz;   // the position transformed
};

// One corner of eight triangles: its positions loaded (x, y, z, and no
// fourth float: a masked load reads nothing past a vertex, the array's
// last included), turned into lanes of x, y and z, and transformed.
// Gathers would be shorter to write and are much slower here.
ClipVertex clip_vertex(const float *m, const float *const corner[8])
{
    const __m128i xyz = _mm_setr_epi32(-1, -1, -1, 0);
    __m256 pair[4];   // corners j and j + 4
    for (int j = 0; j < 4; ++j)
        pair[j] = _mm256_set_m128(_mm_maskload_ps(corner[j + 4], xyz), _mm_maskload_ps(corner[j], xyz));
    const __m256 xy01 = _mm256_unpacklo_ps(pair[0], pair[1]), z01 = _mm256_unpackhi_ps(pair[0], pair[1]);
    const __m256 xy23 = _mm256_unpacklo_ps(pair[2], pair[3]), z23 = _mm256_unpackhi_ps(pair[2], pair[3]);
    const __m256 x = _mm256_shuffle_ps(xy01, xy23, _MM_SHUFFLE(1, 0, 1, 0));
    const __m256 y = _mm256_shuffle_ps(xy01, xy23, _MM_SHUFFLE(3, 2, 3, 2));
    const __m256 z = _mm256_shuffle_ps(z01, z23, _MM_SHUFFLE(1, 0, 1, 0));
    __m256 c[4];
    for (int i = 0; i < 4; ++i)
        c[i] = _mm256_add_ps(
            _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(m[i]), x), _mm256_mul_ps(_mm256_set1_ps(m[4 + i]), y)),
            _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(m[8 + i]), z), _mm256_set1_ps(m[12 + i])));
    return {c[0], c[1], c[2], c[3], x, y, z};
}

// DepthRasterizer::add_transform_error for four corners in double lanes,
// its expressions in its order (glm's m * v sums (m0 x + m1 y) + (m2 z +
// m3)): widens *window and *depth by the bound of GL's float transform
// error at the corners; infinity where w itself is uncertain.
void add_transform_error_four(const TriangleScreen &screen, __m128 px, __m128 py, __m128 pz, __m256d *window,
                              __m256d *depth)
{
    const float *m = screen.view_projection;
    const __m256d x = _mm256_cvtps_pd(px), y = _mm256_cvtps_pd(py), z = _mm256_cvtps_pd(pz);
    const __m256d sign = _mm256_set1_pd(-0.0);
    const auto absolute = [&](__m256d v) { return _mm256_andnot_pd(sign, v); };
    __m256d c[4], bound[4];
    for (int r = 0; r < 4; ++r) {
        const __m256d m0 = _mm256_set1_pd(double(m[r])), m1 = _mm256_set1_pd(double(m[4 + r]));
        const __m256d m2 = _mm256_set1_pd(double(m[8 + r])), m3 = _mm256_set1_pd(double(m[12 + r]));
        const __m256d t0 = _mm256_mul_pd(m0, x), t1 = _mm256_mul_pd(m1, y), t2 = _mm256_mul_pd(m2, z);
        c[r] = _mm256_add_pd(_mm256_add_pd(t0, t1), _mm256_add_pd(t2, m3));
        bound[r] = _mm256_mul_pd(
            _mm256_set1_pd(screen.product_error),
            _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(absolute(t0), absolute(t1)), absolute(t2)), absolute(m3)));
    }
    const __m256d uncertain = _mm256_cmp_pd(c[3], bound[3], _CMP_NGT_UQ);
    const __m256d w = _mm256_sub_pd(c[3], bound[3]);
    const __m256d wx = _mm256_div_pd(
        _mm256_mul_pd(_mm256_set1_pd(screen.error_scale_x),
                      _mm256_add_pd(bound[0], _mm256_mul_pd(absolute(_mm256_div_pd(c[0], c[3])), bound[3]))),
        w);
    const __m256d wy = _mm256_div_pd(
        _mm256_mul_pd(_mm256_set1_pd(screen.error_scale_y),
                      _mm256_add_pd(bound[1], _mm256_mul_pd(absolute(_mm256_div_pd(c[1], c[3])), bound[3]))),
        w);
    const __m256d wz = _mm256_div_pd(
        _mm256_mul_pd(_mm256_set1_pd(0.5),
                      _mm256_add_pd(bound[2], _mm256_mul_pd(absolute(_mm256_div_pd(c[2], c[3])), bound[3]))),
        w);
    // std::max keeps the first of equals; max_pd(a, b) is (a > b ? a : b),
    // the same value for numbers (lanes with a NaN go one at a time).
    const __m256d infinity = _mm256_set1_pd(__builtin_inf());
    *window = _mm256_blendv_pd(_mm256_max_pd(_mm256_max_pd(wx, *window), _mm256_max_pd(wy, *window)), infinity,
                               uncertain);
    *depth = _mm256_blendv_pd(_mm256_max_pd(wz, *depth), infinity, uncertain);
}

// Whether the depth pixels [ceil(lo - first), floor(hi - last)] clamped to
// [0, size) are none, for four lanes in double, as rasterize computes them.
__m256d span_empty(__m128 lo, __m128 hi, double first, double last, int size)
{
    const __m256d start = _mm256_max_pd(_mm256_setzero_pd(),
                                        _mm256_round_pd(_mm256_sub_pd(_mm256_cvtps_pd(lo), _mm256_set1_pd(first)),
                                                        _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC));
    const __m256d end = _mm256_min_pd(
        _mm256_set1_pd(double(size)),
        _mm256_add_pd(_mm256_round_pd(_mm256_sub_pd(_mm256_cvtps_pd(hi), _mm256_set1_pd(last)),
                                      _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC),
                      _mm256_set1_pd(1.0)));
    return _mm256_cmp_pd(start, end, _CMP_GE_OQ);
}

__m256 span_empty(__m256 lo, __m256 hi, double first, double last, int size)
{
    const __m256d low = span_empty(_mm256_castps256_ps128(lo), _mm256_castps256_ps128(hi), first, last, size);
    const __m256d high =
        span_empty(_mm256_extractf128_ps(lo, 1), _mm256_extractf128_ps(hi, 1), first, last, size);
    // Each double lane's mask, all ones or zeros, narrowed to a float lane.
    const __m128 low_mask = _mm256_cvtpd_ps(_mm256_and_pd(low, _mm256_set1_pd(1.0)));
    const __m128 high_mask = _mm256_cvtpd_ps(_mm256_and_pd(high, _mm256_set1_pd(1.0)));
    return _mm256_cmp_ps(_mm256_set_m128(high_mask, low_mask), _mm256_setzero_ps(), _CMP_NEQ_OQ);
}


// rasterize's setup of four projected triangles in double lanes, its
// expressions in its order: the bounding box, the area test, the edges
// with their sample offsets and margins, the depth plane lifted over the
// vertices. Lanes whose area is not positive come back clear in *front.
struct FourSetups {
    alignas(32) double x0[4], y0[4], x1[4], y1[4];
    alignas(16) float ea[3][4], eb[3][4], ec[3][4];
    alignas(16) float za[4], zb[4], zc[4], zcap[4];
};

__m256d select(__m256d mask, __m256d if_true, __m256d if_false) { return _mm256_blendv_pd(if_false, if_true, mask); }
__m256d absolute(__m256d v) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), v); }

int set_up_four(const TriangleScreen &screen, const __m128 *wx, const __m128 *wy, const __m128 *depth,
                FourSetups *out)
{
    const __m256d zero = _mm256_setzero_pd();
    const __m256d first = _mm256_set1_pd(screen.first), last = _mm256_set1_pd(screen.last);
    const __m256d extent = _mm256_set1_pd(screen.extent), float_error = _mm256_set1_pd(screen.float_error);
    __m256d x[3], y[3], d[3];
    for (int i = 0; i < 3; ++i) {
        x[i] = _mm256_cvtps_pd(wx[i]);
        y[i] = _mm256_cvtps_pd(wy[i]);
        d[i] = _mm256_cvtps_pd(depth[i]);
    }
    const __m128 lo_x = _mm_min_ps(_mm_min_ps(wx[0], wx[1]), wx[2]), hi_x = _mm_max_ps(_mm_max_ps(wx[0], wx[1]), wx[2]);
    const __m128 lo_y = _mm_min_ps(_mm_min_ps(wy[0], wy[1]), wy[2]), hi_y = _mm_max_ps(_mm_max_ps(wy[0], wy[1]), wy[2]);
    const __m128 farthest = _mm_max_ps(_mm_max_ps(depth[0], depth[1]), depth[2]);
    _mm256_store_pd(out->x0, _mm256_max_pd(zero, _mm256_round_pd(_mm256_sub_pd(_mm256_cvtps_pd(lo_x), first),
                                                                 _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC)));
    _mm256_store_pd(out->y0, _mm256_max_pd(zero, _mm256_round_pd(_mm256_sub_pd(_mm256_cvtps_pd(lo_y), first),
                                                                 _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC)));
    const __m256d one = _mm256_set1_pd(1.0);
    _mm256_store_pd(out->x1, _mm256_min_pd(_mm256_set1_pd(double(screen.width)),
                                           _mm256_add_pd(_mm256_round_pd(_mm256_sub_pd(_mm256_cvtps_pd(hi_x), last),
                                                                         _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC),
                                                         one)));
    _mm256_store_pd(out->y1, _mm256_min_pd(_mm256_set1_pd(double(screen.height)),
                                           _mm256_add_pd(_mm256_round_pd(_mm256_sub_pd(_mm256_cvtps_pd(hi_y), last),
                                                                         _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC),
                                                         one)));

    // Front faces wind counter-clockwise in window coordinates (y up).
    __m256d area = zero;
    for (int i = 0; i < 3; ++i) {
        const int j = i + 1 == 3 ? 0 : i + 1;
        area = _mm256_add_pd(area, _mm256_sub_pd(_mm256_mul_pd(x[i], y[j]), _mm256_mul_pd(x[j], y[i])));
    }
    const int front = _mm256_movemask_pd(_mm256_cmp_pd(area, zero, _CMP_GT_OQ));
    if (front == 0)
        return 0;

    const __m256d sign = _mm256_set1_pd(-0.0), margin_per_unit = _mm256_set1_pd(screen.edge_margin);
    for (int e = 0; e < 3; ++e) {
        const int f = e + 1 == 3 ? 0 : e + 1;
        const __m256d a = _mm256_sub_pd(y[e], y[f]), b = _mm256_sub_pd(x[f], x[e]);
        const __m256d c = _mm256_xor_pd(sign, _mm256_add_pd(_mm256_mul_pd(a, x[e]), _mm256_mul_pd(b, y[e])));
        const __m256d folded =
            _mm256_add_pd(_mm256_add_pd(c, _mm256_mul_pd(a, select(_mm256_cmp_pd(a, zero, _CMP_GT_OQ), first, last))),
                          _mm256_mul_pd(b, select(_mm256_cmp_pd(b, zero, _CMP_GT_OQ), first, last)));
        const __m256d size = _mm256_add_pd(absolute(a), absolute(b));
        const __m256d margin =
            _mm256_add_pd(_mm256_mul_pd(size, margin_per_unit),
                          _mm256_mul_pd(float_error, _mm256_add_pd(_mm256_mul_pd(size, extent), absolute(folded))));
        _mm_store_ps(out->ea[e], _mm256_cvtpd_ps(a));
        _mm_store_ps(out->eb[e], _mm256_cvtpd_ps(b));
        _mm_store_ps(out->ec[e], _mm256_cvtpd_ps(_mm256_sub_pd(folded, margin)));
    }

    // Depth: the farthest over the samples, never past the farthest vertex.
    const __m128 zcap = _mm256_cvtpd_ps(_mm256_add_pd(_mm256_cvtps_pd(farthest), _mm256_set1_pd(screen.depth_margin)));
    _mm_store_ps(out->zcap, zcap);
    if (!screen.per_pixel_depth) {
        _mm_store_ps(out->za, _mm_setzero_ps());
        _mm_store_ps(out->zb, _mm_setzero_ps());
        _mm_store_ps(out->zc, zcap);
        return front;
    }
    // The plane through the three vertices, lifted so that none lies above it.
    const __m256d ux = _mm256_sub_pd(x[1], x[0]), uy = _mm256_sub_pd(y[1], y[0]);
    const __m256d vx = _mm256_sub_pd(x[2], x[0]), vy = _mm256_sub_pd(y[2], y[0]);
    const __m256d twice = _mm256_sub_pd(_mm256_mul_pd(ux, vy), _mm256_mul_pd(uy, vx));
    const __m256d best_area = select(_mm256_cmp_pd(twice, zero, _CMP_GT_OQ), twice, zero);
    const __m256d du = _mm256_sub_pd(d[1], d[0]), dv = _mm256_sub_pd(d[2], d[0]);
    const __m256d za = _mm256_div_pd(_mm256_sub_pd(_mm256_mul_pd(du, vy), _mm256_mul_pd(dv, uy)), best_area);
    const __m256d zb = _mm256_div_pd(_mm256_sub_pd(_mm256_mul_pd(dv, ux), _mm256_mul_pd(du, vx)), best_area);
    __m256d zc = _mm256_sub_pd(_mm256_sub_pd(d[0], _mm256_mul_pd(za, x[0])), _mm256_mul_pd(zb, y[0]));
    __m256d lift = zero;
    for (int i = 0; i < 3; ++i) {
        const __m256d above =
            _mm256_sub_pd(d[i], _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(za, x[i]), _mm256_mul_pd(zb, y[i])), zc));
        lift = _mm256_max_pd(above, lift);   // std::max(lift, above)
    }
    // zc += lift + za * (last or first) + zb * (last or first): the farthest sample.
    const __m256d za_sample = select(_mm256_cmp_pd(za, zero, _CMP_GT_OQ), last, first);
    const __m256d zb_sample = select(_mm256_cmp_pd(zb, zero, _CMP_GT_OQ), last, first);
    const __m256d lift_to_sample = _mm256_add_pd(lift, _mm256_mul_pd(za, za_sample));
    zc = _mm256_add_pd(zc, _mm256_add_pd(lift_to_sample, _mm256_mul_pd(zb, zb_sample)));
    // zc += depth_margin + float_error * ((|za| + |zb|) * extent + |zc|).
    const __m256d slope = _mm256_add_pd(absolute(za), absolute(zb));
    const __m256d rounding = _mm256_mul_pd(float_error, _mm256_add_pd(_mm256_mul_pd(slope, extent), absolute(zc)));
    zc = _mm256_add_pd(zc, _mm256_add_pd(_mm256_set1_pd(screen.depth_margin), rounding));
    const __m128 za_f = _mm256_cvtpd_ps(za), zb_f = _mm256_cvtpd_ps(zb), zc_f = _mm256_cvtpd_ps(zc);
    // A sliver with no usable plane: its farthest vertex.
    const __m128 infinity = _mm_set1_ps(__builtin_inff());
    const __m128 finite = _mm_and_ps(_mm_and_ps(_mm_cmplt_ps(_mm_andnot_ps(_mm_set1_ps(-0.0f), za_f), infinity),
                                                _mm_cmplt_ps(_mm_andnot_ps(_mm_set1_ps(-0.0f), zb_f), infinity)),
                                     _mm_cmplt_ps(_mm_andnot_ps(_mm_set1_ps(-0.0f), zc_f), infinity));
    _mm_store_ps(out->za, _mm_and_ps(finite, za_f));
    _mm_store_ps(out->zb, _mm_and_ps(finite, zb_f));
    _mm_store_ps(out->zc, _mm_blendv_ps(zcap, zc_f, finite));
    return front;
}

// DepthRasterizer::behind_everything for a triangle's window box and
// nearest corner: whether every tile its depth pixels (and a pixel more
// each way) lie in is nearer everywhere than its nearest corner, by the
// tiles' maxima, a dirty tile's taken first (DepthRasterizer::
// refresh_tile_maximum: the largest of its pixels, which hold no NaN).
bool behind_tiles(const TriangleScreen &screen, float lo_x, float lo_y, float hi_x, float hi_y, float nearest)
{
    const int x0 = std::max(0, int(std::floor(double(lo_x))) - 1);
    const int y0 = std::max(0, int(std::floor(double(lo_y))) - 1);
    const int x1 = std::min(screen.width, int(std::floor(double(hi_x))) + 2);
    const int y1 = std::min(screen.height, int(std::floor(double(hi_y))) + 2);
    if (x0 >= x1 || y0 >= y1)
        return true;
    const float z = float(double(nearest) - screen.depth_margin);
    for (int ty = y0 / tile_size; ty <= (y1 - 1) / tile_size; ++ty)
        for (int tx = x0 / tile_size; tx <= (x1 - 1) / tile_size; ++tx) {
            const std::size_t t = std::size_t(ty) * std::size_t(screen.tiles_x) + std::size_t(tx);
            if (screen.dirty[t]) {
                const float *tile = screen.tiles + t * tile_pixels;
                __m256 m = _mm256_loadu_ps(tile);
                for (int y = 1; y < tile_size; ++y)
                    m = _mm256_max_ps(m, _mm256_loadu_ps(tile + y * tile_size));
                __m128 h = _mm_max_ps(_mm256_castps256_ps128(m), _mm256_extractf128_ps(m, 1));
                h = _mm_max_ps(h, _mm_movehl_ps(h, h));
                h = _mm_max_ss(h, _mm_shuffle_ps(h, h, 1));
                screen.tile_max[t] = _mm_cvtss_f32(h);
                screen.dirty[t] = 0;
            }
            if (!(screen.tile_max[t] < z))
                return false;
        }
    return true;
}

}  // namespace

std::size_t screen_triangles_avx2(const TriangleScreen &screen, const float *positions, const std::uint32_t *indices,
                                  std::size_t count, ScreenedTriangle *out)
{
    const float *m = screen.view_projection;
    const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f);
    const __m256 guard = _mm256_set1_ps(float(guard_band));   // as polygon's float(guard)
    const __m256 sign = _mm256_set1_ps(-0.0f);
    const __m256 scale_x = _mm256_set1_ps(screen.scale_x), scale_y = _mm256_set1_ps(screen.scale_y);
    std::size_t kept = 0;
    for (std::size_t first = 0; first < count; first += 8) {
        const int lanes = count - first < 8 ? int(count - first) : 8;
        // Past the end, the batch's last triangle again, its result dropped.
        ClipVertex v[3];
        for (int corner = 0; corner < 3; ++corner) {
            const float *position[8];
            for (int j = 0; j < 8; ++j) {
                const std::size_t t = first + std::size_t(j < lanes ? j : lanes - 1);
                position[j] = positions + 3 * std::size_t(indices[3 * t + std::size_t(corner)]);
            }
            v[corner] = clip_vertex(m, position);
        }

        // Outside one clip plane with every vertex: nothing to draw.
        const __m256 all = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
        __m256 out_right = all, out_left = all, out_top = all, out_bottom = all, out_far = all, out_near = all;
        __m256 needs_clip = zero;
        for (const ClipVertex &c : v) {
            const __m256 minus_w = _mm256_sub_ps(zero, c.w);
            out_right = _mm256_and_ps(out_right, _mm256_cmp_ps(c.x, c.w, _CMP_GT_OQ));
            out_left = _mm256_and_ps(out_left, _mm256_cmp_ps(c.x, minus_w, _CMP_LT_OQ));
            out_top = _mm256_and_ps(out_top, _mm256_cmp_ps(c.y, c.w, _CMP_GT_OQ));
            out_bottom = _mm256_and_ps(out_bottom, _mm256_cmp_ps(c.y, minus_w, _CMP_LT_OQ));
            out_far = _mm256_and_ps(out_far, _mm256_cmp_ps(c.z, c.w, _CMP_GT_OQ));
            const __m256 before_near = _mm256_cmp_ps(c.z, minus_w, _CMP_LT_OQ);
            out_near = _mm256_and_ps(out_near, before_near);
            // x > g || x < -g is |x| > g, NaN included (false either way).
            const __m256 g = _mm256_mul_ps(guard, c.w);
            needs_clip = _mm256_or_ps(needs_clip, before_near);
            needs_clip = _mm256_or_ps(needs_clip, _mm256_cmp_ps(_mm256_andnot_ps(sign, c.x), g, _CMP_GT_OQ));
            needs_clip = _mm256_or_ps(needs_clip, _mm256_cmp_ps(_mm256_andnot_ps(sign, c.y), g, _CMP_GT_OQ));
            needs_clip = _mm256_or_ps(needs_clip, _mm256_cmp_ps(c.w, zero, _CMP_NGT_UQ));
        }
        const __m256 all_out =
            _mm256_or_ps(_mm256_or_ps(_mm256_or_ps(out_right, out_left), _mm256_or_ps(out_top, out_bottom)),
                         _mm256_or_ps(out_far, out_near));
        // polygon's test of the first vertex's sum; a non-finite one draws nothing.
        const __m256 sum = _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(v[0].x, v[0].y), v[0].z), v[0].w);
        const __m256 finite = _mm256_cmp_ps(_mm256_sub_ps(sum, sum), zero, _CMP_EQ_OQ);
        const int drawn = _mm256_movemask_ps(_mm256_andnot_ps(all_out, finite)) & ((1 << lanes) - 1);
        if (drawn == 0)
            continue;
        int one_at_a_time = _mm256_movemask_ps(needs_clip) & drawn;

        // The winding: the sign of det(x, y, w), before any division.
        const ClipVertex &p = v[0], &q = v[1], &r = v[2];
        const __m256 winding = _mm256_add_ps(
            _mm256_sub_ps(_mm256_mul_ps(p.x, _mm256_sub_ps(_mm256_mul_ps(q.y, r.w), _mm256_mul_ps(q.w, r.y))),
                          _mm256_mul_ps(p.y, _mm256_sub_ps(_mm256_mul_ps(q.x, r.w), _mm256_mul_ps(q.w, r.x)))),
            _mm256_mul_ps(p.w, _mm256_sub_ps(_mm256_mul_ps(q.x, r.y), _mm256_mul_ps(q.y, r.x))));
        int projected = _mm256_movemask_ps(_mm256_cmp_ps(winding, zero, _CMP_GT_OQ)) & drawn & ~one_at_a_time;
        __m256 wx[3] = {}, wy[3] = {}, depth[3] = {};
        if (projected != 0) {
            for (int i = 0; i < 3; ++i) {
                const __m256 inv = _mm256_div_ps(one, v[i].w);
                wx[i] = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(v[i].x, inv), one), scale_x);
                wy[i] = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(v[i].y, inv), one), scale_y);
                depth[i] = _mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(v[i].z, inv), half), half);
            }
            // The depth pixels the triangle may cover wholly: none for most.
            const __m256 lo_x = _mm256_min_ps(_mm256_min_ps(wx[0], wx[1]), wx[2]);
            const __m256 hi_x = _mm256_max_ps(_mm256_max_ps(wx[0], wx[1]), wx[2]);
            const __m256 lo_y = _mm256_min_ps(_mm256_min_ps(wy[0], wy[1]), wy[2]);
            const __m256 hi_y = _mm256_max_ps(_mm256_max_ps(wy[0], wy[1]), wy[2]);
            if (!screen.keep_partial) {
                const __m256 empty = _mm256_or_ps(span_empty(lo_x, hi_x, screen.first, screen.last, screen.width),
                                                  span_empty(lo_y, hi_y, screen.first, screen.last, screen.height));
                projected &= ~_mm256_movemask_ps(empty);
            } else {
                // Drawn nearest first, most of a mesh's later triangles
                // lie behind what is there already: dropped before their
                // setup and transform error.
                alignas(32) float box[4][8], nearest[8];
                _mm256_store_ps(box[0], lo_x);
                _mm256_store_ps(box[1], lo_y);
                _mm256_store_ps(box[2], hi_x);
                _mm256_store_ps(box[3], hi_y);
                _mm256_store_ps(nearest, _mm256_min_ps(_mm256_min_ps(depth[0], depth[1]), depth[2]));
                for (int bits = projected; bits != 0; bits &= bits - 1) {
                    const int lane = __builtin_ctz(unsigned(bits));
                    if (behind_tiles(screen, box[0][lane], box[1][lane], box[2][lane], box[3][lane], nearest[lane]))
                        projected &= ~(1 << lane);
                }
            }
        }
        // Set up, four lanes at a time; a lane whose area is not positive drops out.
        FourSetups setups[2];
        for (int four = 0; four < 2; ++four)
            if (projected >> (4 * four) & 15) {
                __m128 x[3], y[3], z[3];
                for (int i = 0; i < 3; ++i) {
                    x[i] = four ? _mm256_extractf128_ps(wx[i], 1) : _mm256_castps256_ps128(wx[i]);
                    y[i] = four ? _mm256_extractf128_ps(wy[i], 1) : _mm256_castps256_ps128(wy[i]);
                    z[i] = four ? _mm256_extractf128_ps(depth[i], 1) : _mm256_castps256_ps128(depth[i]);
                }
                const int front = set_up_four(screen, x, y, z, &setups[four]);
                projected &= ~((15 & ~front) << (4 * four));
            }
        // Merged coverage: the transform error's bound, four lanes at a
        // time; a lane where it is not a number goes one at a time.
        alignas(32) double error_window[8], error_depth[8];
        if (screen.keep_partial)
            for (int four = 0; four < 2; ++four) {
                if (!(projected >> (4 * four) & 15))
                    continue;
                __m256d window = _mm256_setzero_pd(), depth_error = _mm256_setzero_pd();
                for (const ClipVertex &c : v) {
                    const auto half_of = [&](__m256 lanes) {
                        return four ? _mm256_extractf128_ps(lanes, 1) : _mm256_castps256_ps128(lanes);
                    };
                    add_transform_error_four(screen, half_of(c.px), half_of(c.py), half_of(c.pz), &window,
                                             &depth_error);
                }
                const int not_a_number = _mm256_movemask_pd(_mm256_cmp_pd(
                    _mm256_add_pd(window, depth_error), _mm256_add_pd(window, depth_error), _CMP_UNORD_Q));
                projected &= ~(not_a_number << (4 * four));
                one_at_a_time |= (not_a_number << (4 * four)) & drawn;
                _mm256_store_pd(error_window + 4 * four, window);
                _mm256_store_pd(error_depth + 4 * four, depth_error);
            }
        const int kept_lanes = projected | one_at_a_time;
        for (int lane = 0; lane < lanes; ++lane) {
            if (!(kept_lanes >> lane & 1))
                continue;
            ScreenedTriangle &t = out[kept++];
            t.triangle = std::uint32_t(first) + std::uint32_t(lane);
            t.set_up = (projected >> lane & 1) != 0;
            if (!t.set_up)
                continue;
            const FourSetups &f = setups[lane / 4];
            const int l = lane % 4;
            PolygonSetup &setup = t.setup;
            setup.edges = 3;
            for (int e = 0; e < 3; ++e) {
                setup.ea[e] = f.ea[e][l];
                setup.eb[e] = f.eb[e][l];
                setup.ec[e] = f.ec[e][l];
            }
            setup.za = f.za[l];
            setup.zb = f.zb[l];
            setup.zc = f.zc[l];
            setup.zcap = f.zcap[l];
            setup.x0 = int(f.x0[l]);
            setup.y0 = int(f.y0[l]);
            setup.x1 = int(f.x1[l]);
            setup.y1 = int(f.y1[l]);
            if (screen.keep_partial) {
                const auto lane_of = [&](__m256 lanes) {
                    alignas(32) float all[8];
                    _mm256_store_ps(all, lanes);
                    return all[lane];
                };
                for (int i = 0; i < 3; ++i) {
                    t.wx[i] = lane_of(wx[i]);
                    t.wy[i] = lane_of(wy[i]);
                    t.depth[i] = lane_of(depth[i]);
                }
                t.error_window = error_window[lane];
                t.error_depth = error_depth[lane];
            }
        }
    }
    return kept;
}

}  // namespace occu::raster
