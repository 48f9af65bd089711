// SPDX-License-Identifier: MIT
#include "raster/occludee_kernels.h"

#include <immintrin.h>

#include <algorithm>
#include <limits>

#include "raster/raster_kernels.h"

namespace occu::raster {

namespace {

__m256d load(const double *lanes) { return _mm256_loadu_pd(lanes); }

// A corner per lane in clip space, c = m (x, y, z, 1), and per row the
// bound of its rounding, b = error (|m| (|x|, |y|, |z|, 1)), in the
// scalar's order of operations (no fused multiply-add).
void clip_and_bound(const double *m, const double *magnitude, __m256d error, __m256d x, __m256d y, __m256d z,
                    __m256d c[4], __m256d b[4])
{
    const __m256d sign = _mm256_set1_pd(-0.0);
    const __m256d ax = _mm256_andnot_pd(sign, x), ay = _mm256_andnot_pd(sign, y), az = _mm256_andnot_pd(sign, z);
    for (int r = 0; r < 4; ++r) {
        c[r] = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(m[r]), x), _mm256_mul_pd(_mm256_set1_pd(m[4 + r]), y)),
                             _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(m[8 + r]), z), _mm256_set1_pd(m[12 + r])));
        b[r] = _mm256_mul_pd(error, _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(magnitude[r]), ax),
                                                                _mm256_mul_pd(_mm256_set1_pd(magnitude[4 + r]), ay)),
                                                  _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(magnitude[8 + r]), az),
                                                                _mm256_set1_pd(magnitude[12 + r]))));
    }
}

}  // namespace

OccludeeVerdicts occludee_triangles_avx2(const double *m, const double *magnitude, double product_error,
                                         const float *const corners[occludee_lanes][3], double sx, double sy,
                                         double edge_grow, double depth_margin, OccludeePolygons &out)
{
    const __m256d sign = _mm256_set1_pd(-0.0), zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0),
                  half = _mm256_set1_pd(0.5);
    const __m256d largest = _mm256_set1_pd(std::numeric_limits<double>::max());
    const __m256d error = _mm256_set1_pd(product_error), scale_x = _mm256_set1_pd(sx), scale_y = _mm256_set1_pd(sy);
    out.corners = 3;
    // Per lane: a corner unknown; every corner beyond side s (all ones to
    // begin with); a corner with w <= b.w; the largest window and depth
    // moves, max(new, old) as std::max(old, new) keeps the old on a tie or
    // NaN.
    __m256d unknown = zero, infinite = zero, window = zero, depth = zero;
    __m256d beyond[5];
    for (__m256d &side : beyond)
        side = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    for (int i = 0; i < 3; ++i) {
        const auto lanes = [&](int a) {
            return _mm256_cvtps_pd(_mm_setr_ps(corners[0][i][a], corners[1][i][a], corners[2][i][a], corners[3][i][a]));
        };
        __m256d c[4], b[4];
        clip_and_bound(m, magnitude, error, lanes(0), lanes(1), lanes(2), c, b);
        const __m256d sum = _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(c[0], c[1]), c[2]), c[3]);
        const __m256d minus_w = _mm256_xor_pd(c[3], sign);
        unknown = _mm256_or_pd(unknown, _mm256_or_pd(_mm256_cmp_pd(_mm256_andnot_pd(sign, sum), largest, _CMP_NLE_UQ),
                                                     _mm256_or_pd(_mm256_cmp_pd(c[3], zero, _CMP_NGT_UQ),
                                                                  _mm256_cmp_pd(c[2], minus_w, _CMP_LT_OQ))));
        beyond[0] = _mm256_and_pd(beyond[0], _mm256_cmp_pd(c[0], c[3], _CMP_GT_OQ));
        beyond[1] = _mm256_and_pd(beyond[1], _mm256_cmp_pd(c[0], minus_w, _CMP_LT_OQ));
        beyond[2] = _mm256_and_pd(beyond[2], _mm256_cmp_pd(c[1], c[3], _CMP_GT_OQ));
        beyond[3] = _mm256_and_pd(beyond[3], _mm256_cmp_pd(c[1], minus_w, _CMP_LT_OQ));
        beyond[4] = _mm256_and_pd(beyond[4], _mm256_cmp_pd(c[2], c[3], _CMP_GT_OQ));
        const __m256d nx = _mm256_div_pd(c[0], c[3]), ny = _mm256_div_pd(c[1], c[3]), nz = _mm256_div_pd(c[2], c[3]);
        _mm256_storeu_pd(out.x[i], _mm256_mul_pd(_mm256_add_pd(nx, one), scale_x));
        _mm256_storeu_pd(out.y[i], _mm256_mul_pd(_mm256_add_pd(ny, one), scale_y));
        _mm256_storeu_pd(out.z[i], _mm256_add_pd(_mm256_mul_pd(nz, half), half));
        infinite = _mm256_or_pd(infinite, _mm256_cmp_pd(c[3], b[3], _CMP_NGT_UQ));
        const __m256d w = _mm256_sub_pd(c[3], b[3]);
        const __m256d ex = _mm256_div_pd(_mm256_mul_pd(scale_x, _mm256_add_pd(b[0], _mm256_mul_pd(_mm256_andnot_pd(sign, nx), b[3]))), w);
        const __m256d ey = _mm256_div_pd(_mm256_mul_pd(scale_y, _mm256_add_pd(b[1], _mm256_mul_pd(_mm256_andnot_pd(sign, ny), b[3]))), w);
        const __m256d ez = _mm256_div_pd(_mm256_mul_pd(half, _mm256_add_pd(b[2], _mm256_mul_pd(_mm256_andnot_pd(sign, nz), b[3]))), w);
        window = _mm256_max_pd(ey, _mm256_max_pd(ex, window));
        depth = _mm256_max_pd(ez, depth);
    }
    // Once infinite, a lane's maxima stay infinite in the scalar order.
    const __m256d inf = _mm256_set1_pd(std::numeric_limits<double>::infinity());
    window = _mm256_blendv_pd(window, inf, infinite);
    depth = _mm256_blendv_pd(depth, inf, infinite);
    const __m256d beyond_any =
        _mm256_or_pd(_mm256_or_pd(_mm256_or_pd(beyond[0], beyond[1]), _mm256_or_pd(beyond[2], beyond[3])), beyond[4]);
    const __m256d too_far = _mm256_or_pd(_mm256_cmp_pd(window, _mm256_set1_pd(1e6), _CMP_NLT_UQ),
                                         _mm256_cmp_pd(depth, one, _CMP_NLT_UQ));
    const unsigned unknown_lanes = unsigned(_mm256_movemask_pd(unknown));
    const unsigned skipped = unsigned(_mm256_movemask_pd(beyond_any)) & ~unknown_lanes;
    const OccludeeVerdicts verdicts{unknown_lanes | (unsigned(_mm256_movemask_pd(too_far)) & ~unknown_lanes & ~skipped),
                                    skipped};
    __m256d z[3];
    for (int i = 0; i < 3; ++i) {
        z[i] = _mm256_sub_pd(load(out.z[i]), depth);
        _mm256_storeu_pd(out.z[i], z[i]);
    }
    // std::min({z0, z1, z2}): the first of the least.
    const __m256d nearest = _mm256_min_pd(z[2], _mm256_min_pd(z[1], z[0]));
    _mm256_storeu_pd(out.floor_z, _mm256_sub_pd(nearest, _mm256_set1_pd(depth_margin)));
    _mm256_storeu_pd(out.grow, _mm256_add_pd(_mm256_set1_pd(edge_grow), window));
    return verdicts;
}

OccludeeVerdicts occludee_triangle_avx2(const double *m, const double *magnitude, double product_error,
                                        const float *const corners[3], double sx, double sy, double edge_grow,
                                        double depth_margin, OccludeePolygons &out)
{
    constexpr unsigned every_lane = (1u << occludee_lanes) - 1;
    // Lane i is corner i; lane 3 repeats corner 2, so that it changes no
    // side beyond.
    const auto lanes = [&](int a) {
        return _mm256_setr_pd(corners[0][a], corners[1][a], corners[2][a], corners[2][a]);
    };
    const __m256d sign = _mm256_set1_pd(-0.0);
    __m256d c[4], b[4];
    clip_and_bound(m, magnitude, _mm256_set1_pd(product_error), lanes(0), lanes(1), lanes(2), c, b);
    out.corners = 3;
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5);
    const __m256d largest = _mm256_set1_pd(std::numeric_limits<double>::max());
    const __m256d sum = _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(c[0], c[1]), c[2]), c[3]);
    const __m256d minus_w = _mm256_xor_pd(c[3], sign);
    const __m256d unknown = _mm256_or_pd(_mm256_cmp_pd(_mm256_andnot_pd(sign, sum), largest, _CMP_NLE_UQ),
                                         _mm256_or_pd(_mm256_cmp_pd(c[3], zero, _CMP_NGT_UQ),
                                                      _mm256_cmp_pd(c[2], minus_w, _CMP_LT_OQ)));
    if (_mm256_movemask_pd(unknown) != 0)
        return {every_lane, 0};
    const auto every = [](__m256d mask) { return _mm256_movemask_pd(mask) == 15; };
    if (every(_mm256_cmp_pd(c[0], c[3], _CMP_GT_OQ)) || every(_mm256_cmp_pd(c[0], minus_w, _CMP_LT_OQ)) ||
        every(_mm256_cmp_pd(c[1], c[3], _CMP_GT_OQ)) || every(_mm256_cmp_pd(c[1], minus_w, _CMP_LT_OQ)) ||
        every(_mm256_cmp_pd(c[2], c[3], _CMP_GT_OQ)))
        return {0, every_lane};
    const __m256d nx = _mm256_div_pd(c[0], c[3]), ny = _mm256_div_pd(c[1], c[3]), nz = _mm256_div_pd(c[2], c[3]);
    double wx[4], wy[4], wz[4], ex[4], ey[4], ez[4];
    _mm256_storeu_pd(wx, _mm256_mul_pd(_mm256_add_pd(nx, one), _mm256_set1_pd(sx)));
    _mm256_storeu_pd(wy, _mm256_mul_pd(_mm256_add_pd(ny, one), _mm256_set1_pd(sy)));
    _mm256_storeu_pd(wz, _mm256_add_pd(_mm256_mul_pd(nz, half), half));
    double window = std::numeric_limits<double>::infinity(), depth = window;
    if (_mm256_movemask_pd(_mm256_cmp_pd(c[3], b[3], _CMP_NGT_UQ)) == 0) {
        const __m256d w = _mm256_sub_pd(c[3], b[3]);
        _mm256_storeu_pd(ex, _mm256_div_pd(_mm256_mul_pd(_mm256_set1_pd(sx),
                                                         _mm256_add_pd(b[0], _mm256_mul_pd(_mm256_andnot_pd(sign, nx), b[3]))), w));
        _mm256_storeu_pd(ey, _mm256_div_pd(_mm256_mul_pd(_mm256_set1_pd(sy),
                                                         _mm256_add_pd(b[1], _mm256_mul_pd(_mm256_andnot_pd(sign, ny), b[3]))), w));
        _mm256_storeu_pd(ez, _mm256_div_pd(_mm256_mul_pd(half, _mm256_add_pd(b[2], _mm256_mul_pd(_mm256_andnot_pd(sign, nz), b[3]))), w));
        // The scalar order of the maxima, corner by corner.
        window = depth = 0.0;
        for (int i = 0; i < 3; ++i) {
            window = std::max({window, ex[i], ey[i]});
            depth = std::max(depth, ez[i]);
        }
    }
    if (!(window < 1e6 && depth < 1.0))
        return {every_lane, 0};
    // Every lane holds the triangle, as the lanes version's lanes past
    // the end do.
    for (int i = 0; i < 3; ++i) {
        _mm256_storeu_pd(out.x[i], _mm256_set1_pd(wx[i]));
        _mm256_storeu_pd(out.y[i], _mm256_set1_pd(wy[i]));
        _mm256_storeu_pd(out.z[i], _mm256_set1_pd(wz[i] - depth));
    }
    _mm256_storeu_pd(out.floor_z, _mm256_set1_pd(std::min({wz[0] - depth, wz[1] - depth, wz[2] - depth}) - depth_margin));
    _mm256_storeu_pd(out.grow, _mm256_set1_pd(edge_grow + window));
    return {0, 0};
}

namespace {

// The setup for n corners, its loops unrolled.
template <int n>
void setup_lanes(OccludeePolygons &p, double width, double height, double depth_margin)
{
    const __m256d sign = _mm256_set1_pd(-0.0), zero = _mm256_setzero_pd();
    const auto abs = [&](__m256d v) { return _mm256_andnot_pd(sign, v); };
    const __m256d grow = load(p.grow);
    __m256d x[4], y[4], z[4];
    for (int i = 0; i < n; ++i) {
        x[i] = load(p.x[i]);
        y[i] = load(p.y[i]);
        z[i] = load(p.z[i]);
    }
    // glm::min(lo, a) is (a < lo) ? a : lo, min_pd(a, lo); max likewise.
    __m256d area = zero, area_error = _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(2.0 * n), grow), grow);
    __m256d lo_x = _mm256_set1_pd(1e300), lo_y = lo_x, hi_x = _mm256_set1_pd(-1e300), hi_y = hi_x;
    for (int i = 0; i < n; ++i) {
        const int b = i + 1 < n ? i + 1 : 0, before = i > 0 ? i - 1 : n - 1;
        area = _mm256_add_pd(area, _mm256_sub_pd(_mm256_mul_pd(x[i], y[b]), _mm256_mul_pd(x[b], y[i])));
        area_error = _mm256_add_pd(area_error, _mm256_mul_pd(grow, _mm256_add_pd(abs(_mm256_sub_pd(x[b], x[before])),
                                                                                 abs(_mm256_sub_pd(y[b], y[before])))));
        lo_x = _mm256_min_pd(x[i], lo_x);
        lo_y = _mm256_min_pd(y[i], lo_y);
        hi_x = _mm256_max_pd(x[i], hi_x);
        hi_y = _mm256_max_pd(y[i], hi_y);
    }
    p.away = unsigned(_mm256_movemask_pd(_mm256_cmp_pd(area, _mm256_xor_pd(area_error, sign), _CMP_LT_OQ)));
    const __m256d edge_on = _mm256_cmp_pd(area, area_error, _CMP_LE_OQ);
    const __m256d reversed = _mm256_cmp_pd(area, zero, _CMP_LT_OQ);
    __m256d cx[4], cy[4], cz[4];
    for (int i = 0; i < n; ++i) {
        cx[i] = _mm256_blendv_pd(x[i], x[n - 1 - i], reversed);
        cy[i] = _mm256_blendv_pd(y[i], y[n - 1 - i], reversed);
        cz[i] = _mm256_blendv_pd(z[i], z[n - 1 - i], reversed);
    }
    // std::max(-1, f) is (-1 < f) ? f : -1, max_pd(f, -1); std::min(size, f) likewise.
    constexpr int down = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
    const __m256d minus_one = _mm256_set1_pd(-1.0);
    _mm256_storeu_pd(p.x_lo, _mm256_max_pd(_mm256_round_pd(_mm256_sub_pd(lo_x, grow), down), minus_one));
    _mm256_storeu_pd(p.y_lo, _mm256_max_pd(_mm256_round_pd(_mm256_sub_pd(lo_y, grow), down), minus_one));
    _mm256_storeu_pd(p.x_hi, _mm256_min_pd(_mm256_round_pd(_mm256_add_pd(hi_x, grow), down), _mm256_set1_pd(width)));
    _mm256_storeu_pd(p.y_hi, _mm256_min_pd(_mm256_round_pd(_mm256_add_pd(hi_y, grow), down), _mm256_set1_pd(height)));
    // std::max(e, 0) is (e < 0) ? 0 : e, max_pd(0, e).
    for (int e = 0; e < n; ++e) {
        const int b = e + 1 < n ? e + 1 : 0;
        const __m256d ea = _mm256_sub_pd(cy[e], cy[b]), eb = _mm256_sub_pd(cx[b], cx[e]);
        const __m256d at = _mm256_xor_pd(_mm256_add_pd(_mm256_mul_pd(ea, cx[e]), _mm256_mul_pd(eb, cy[e])), sign);
        const __m256d ec = _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(at, _mm256_max_pd(zero, ea)), _mm256_max_pd(zero, eb)),
                                         _mm256_mul_pd(_mm256_add_pd(abs(ea), abs(eb)), grow));
        _mm256_storeu_pd(p.ea[e], ea);
        _mm256_storeu_pd(p.eb[e], eb);
        _mm256_storeu_pd(p.ec[e], ec);
    }
    // std::min(z, 0) is (0 < z) ? 0 : z, min_pd(0, z).
    const __m256d ux = _mm256_sub_pd(cx[1], cx[0]), uy = _mm256_sub_pd(cy[1], cy[0]);
    const __m256d vx = _mm256_sub_pd(cx[2], cx[0]), vy = _mm256_sub_pd(cy[2], cy[0]);
    const __m256d twice = _mm256_sub_pd(_mm256_mul_pd(ux, vy), _mm256_mul_pd(uy, vx));
    const __m256d planar = _mm256_andnot_pd(edge_on, _mm256_cmp_pd(twice, zero, _CMP_GT_OQ));
    const __m256d du = _mm256_sub_pd(cz[1], cz[0]), dv = _mm256_sub_pd(cz[2], cz[0]);
    const __m256d za = _mm256_div_pd(_mm256_sub_pd(_mm256_mul_pd(du, vy), _mm256_mul_pd(dv, uy)), twice);
    const __m256d zb = _mm256_div_pd(_mm256_sub_pd(_mm256_mul_pd(dv, ux), _mm256_mul_pd(du, vx)), twice);
    const __m256d zc = _mm256_sub_pd(
        _mm256_add_pd(_mm256_add_pd(_mm256_sub_pd(_mm256_sub_pd(cz[0], _mm256_mul_pd(za, cx[0])), _mm256_mul_pd(zb, cy[0])),
                                    _mm256_min_pd(zero, za)),
                      _mm256_min_pd(zero, zb)),
        _mm256_set1_pd(depth_margin));
    _mm256_storeu_pd(p.za, _mm256_blendv_pd(zero, za, planar));
    _mm256_storeu_pd(p.zb, _mm256_blendv_pd(zero, zb, planar));
    _mm256_storeu_pd(p.zc, _mm256_blendv_pd(load(p.floor_z), zc, planar));
}

}  // namespace

void occludee_setup_avx2(OccludeePolygons &p, double width, double height, double depth_margin)
{
    if (p.corners == 3)
        setup_lanes<3>(p, width, height, depth_margin);
    else
        setup_lanes<4>(p, width, height, depth_margin);
}

bool box_corners_window_avx2(const double *m, const float lo[3], const float hi[3], double sx, double sy,
                             double window_x[8], double window_y[8], double depth[8])
{
    const __m256d x = _mm256_setr_pd(lo[0], hi[0], lo[0], hi[0]), y = _mm256_setr_pd(lo[1], lo[1], hi[1], hi[1]);
    const __m256d one = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5), zero = _mm256_setzero_pd();
    const __m256d scale_x = _mm256_set1_pd(sx), scale_y = _mm256_set1_pd(sy), sign = _mm256_set1_pd(-0.0);
    for (int g = 0; g < 2; ++g) {
        const __m256d z = _mm256_set1_pd(g ? hi[2] : lo[2]);
        __m256d row[4];
        for (int r = 0; r < 4; ++r)
            row[r] = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(m[r]), x), _mm256_mul_pd(_mm256_set1_pd(m[4 + r]), y)),
                                   _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(m[8 + r]), z), _mm256_set1_pd(m[12 + r])));
        const __m256d outside = _mm256_or_pd(_mm256_cmp_pd(row[3], zero, _CMP_NGT_UQ),
                                             _mm256_cmp_pd(row[2], _mm256_xor_pd(row[3], sign), _CMP_LT_OQ));
        if (_mm256_movemask_pd(outside) != 0)
            return false;
        _mm256_storeu_pd(window_x + 4 * g, _mm256_mul_pd(_mm256_add_pd(_mm256_div_pd(row[0], row[3]), one), scale_x));
        _mm256_storeu_pd(window_y + 4 * g, _mm256_mul_pd(_mm256_add_pd(_mm256_div_pd(row[1], row[3]), one), scale_y));
        _mm256_storeu_pd(depth + 4 * g, _mm256_add_pd(_mm256_mul_pd(_mm256_div_pd(row[2], row[3]), half), half));
    }
    return true;
}

namespace {

// polygon_behind_avx2 for a polygon of `edges` corners: its coefficients
// broadcast once for all its tiles.
template <int edges>
bool polygon_tiles_behind(const OccludeePolygons &p, int lane, const float *tiles, const float *tile_max, int tiles_x,
                          int x0, int y0, int x1, int y1)
{
    const double za = p.za[lane], zb = p.zb[lane], zc = p.zc[lane], floor_z = p.floor_z[lane];
    const __m256d zero = _mm256_setzero_pd();
    const __m256d plane_b = _mm256_set1_pd(zb), plane_c = _mm256_set1_pd(zc), floor = _mm256_set1_pd(floor_z);
    __m256d edge_b[edges], edge_c[edges];
    for (int e = 0; e < edges; ++e) {
        edge_b[e] = _mm256_set1_pd(p.eb[e][lane]);
        edge_c[e] = _mm256_set1_pd(p.ec[e][lane]);
    }
    const __m128i column_lane = _mm_setr_epi32(0, 1, 2, 3);
    for (int ty = y0 / tile_size; ty <= (y1 - 1) / tile_size; ++ty)
        for (int tx = x0 / tile_size; tx <= (x1 - 1) / tile_size; ++tx) {
            // DepthRasterizer::polygon_behind's tile: settled by its
            // farthest depth where that is nearer than the polygon's
            // nearest over it, the same double expression.
            const int tx0 = std::max(x0, tx * tile_size), tx1 = std::min(x1, (tx + 1) * tile_size);
            const int ty0 = std::max(y0, ty * tile_size), ty1 = std::min(y1, (ty + 1) * tile_size);
            const double tile_nearest =
                std::max(floor_z, za * (za < 0.0 ? tx1 - 1 : tx0) + zb * (zb < 0.0 ? ty1 - 1 : ty0) + zc);
            const std::size_t t = std::size_t(ty) * std::size_t(tiles_x) + std::size_t(tx);
            if (double(tile_max[t]) < tile_nearest)
                continue;
            const float *tile = tiles + t * tile_pixels;
            const int x8 = tx * tile_size, y8 = ty * tile_size;
            const int c0 = tx0 - x8, c1 = tx1 - x8;
            // The row's halves of four columns, and which of their lanes
            // lie in [c0, c1); the pixel's edges and plane as the scalar
            // loop's, (a x + b y) + c.
            for (int half = c0 / 4 * 4; half < c1; half += 4) {
                const __m128i column = _mm_add_epi32(column_lane, _mm_set1_epi32(half));
                const __m256d chosen = _mm256_castsi256_pd(_mm256_cvtepi32_epi64(_mm_and_si128(
                    _mm_cmpgt_epi32(column, _mm_set1_epi32(c0 - 1)), _mm_cmpgt_epi32(_mm_set1_epi32(c1), column))));
                const __m256d x = _mm256_cvtepi32_pd(_mm_add_epi32(column, _mm_set1_epi32(x8)));
                __m256d ex[edges];
                for (int e = 0; e < edges; ++e)
                    ex[e] = _mm256_mul_pd(_mm256_set1_pd(p.ea[e][lane]), x);
                const __m256d zx = _mm256_mul_pd(_mm256_set1_pd(za), x);
                for (int y = ty0; y < ty1; ++y) {
                    const __m256d row = _mm256_set1_pd(double(y));
                    __m256d reached = chosen;
                    for (int e = 0; e < edges; ++e)
                        reached = _mm256_and_pd(
                            reached,
                            _mm256_cmp_pd(_mm256_add_pd(_mm256_add_pd(ex[e], _mm256_mul_pd(edge_b[e], row)), edge_c[e]),
                                          zero, _CMP_GE_OQ));
                    // max_pd(plane, floor) is floor where the plane is not
                    // above it (NaN included), as std::max(floor, plane).
                    const __m256d nearest =
                        _mm256_max_pd(_mm256_add_pd(_mm256_add_pd(zx, _mm256_mul_pd(plane_b, row)), plane_c), floor);
                    const __m256d depth = _mm256_cvtps_pd(_mm_loadu_ps(tile + (y - y8) * tile_size + half));
                    if (_mm256_movemask_pd(_mm256_and_pd(reached, _mm256_cmp_pd(depth, nearest, _CMP_NLT_UQ))) != 0)
                        return false;
                }
            }
        }
    return true;
}

}  // namespace

bool polygon_behind_avx2(const OccludeePolygons &p, int lane, const float *tiles, const float *tile_max, int tiles_x,
                         int x0, int y0, int x1, int y1)
{
    return p.corners == 3 ? polygon_tiles_behind<3>(p, lane, tiles, tile_max, tiles_x, x0, y0, x1, y1)
                          : polygon_tiles_behind<4>(p, lane, tiles, tile_max, tiles_x, x0, y0, x1, y1);
}

}  // namespace occu::raster
