// SPDX-License-Identifier: MIT
#include "raster/occludee_kernels.h"

#include <immintrin.h>

#include <limits>

#include "raster/raster_kernels.h"

namespace occu::raster {

bool occludee_corners_avx2(const double *m, const double *magnitude, double product_error,
                           const float *const corners[3], double sx, double sy, OccludeeCorners &out)
{
    // Lane i is corner i; lane 3 repeats corner 2, so that it changes no
    // bound, maximum or side.
    const auto lanes = [&](int a) {
        return _mm256_setr_pd(corners[0][a], corners[1][a], corners[2][a], corners[2][a]);
    };
    const __m256d x = lanes(0), y = lanes(1), z = lanes(2);
    const __m256d sign = _mm256_set1_pd(-0.0);
    const __m256d ax = _mm256_andnot_pd(sign, x), ay = _mm256_andnot_pd(sign, y), az = _mm256_andnot_pd(sign, z);
    const __m256d error = _mm256_set1_pd(product_error);
    __m256d c[4], b[4];
    for (int r = 0; r < 4; ++r) {
        c[r] = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(m[r]), x), _mm256_mul_pd(_mm256_set1_pd(m[4 + r]), y)),
                             _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(m[8 + r]), z), _mm256_set1_pd(m[12 + r])));
        b[r] = _mm256_mul_pd(error, _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(magnitude[r]), ax),
                                                                _mm256_mul_pd(_mm256_set1_pd(magnitude[4 + r]), ay)),
                                                  _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(magnitude[8 + r]), az),
                                                                _mm256_set1_pd(magnitude[12 + r]))));
    }
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5);
    const __m256d largest = _mm256_set1_pd(std::numeric_limits<double>::max());
    const __m256d sum = _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(c[0], c[1]), c[2]), c[3]);
    const __m256d minus_w = _mm256_xor_pd(c[3], sign);
    const __m256d unknown = _mm256_or_pd(_mm256_cmp_pd(_mm256_andnot_pd(sign, sum), largest, _CMP_NLE_UQ),
                                         _mm256_or_pd(_mm256_cmp_pd(c[3], zero, _CMP_NGT_UQ),
                                                      _mm256_cmp_pd(c[2], minus_w, _CMP_LT_OQ)));
    if (_mm256_movemask_pd(unknown) != 0)
        return false;
    const auto every = [](__m256d mask) { return _mm256_movemask_pd(mask) == 15; };
    out.beyond = unsigned(every(_mm256_cmp_pd(c[0], c[3], _CMP_GT_OQ))) << 0 |
                 unsigned(every(_mm256_cmp_pd(c[0], minus_w, _CMP_LT_OQ))) << 1 |
                 unsigned(every(_mm256_cmp_pd(c[1], c[3], _CMP_GT_OQ))) << 2 |
                 unsigned(every(_mm256_cmp_pd(c[1], minus_w, _CMP_LT_OQ))) << 3 |
                 unsigned(every(_mm256_cmp_pd(c[2], c[3], _CMP_GT_OQ))) << 4;
    const __m256d nx = _mm256_div_pd(c[0], c[3]), ny = _mm256_div_pd(c[1], c[3]), nz = _mm256_div_pd(c[2], c[3]);
    _mm256_storeu_pd(out.x, _mm256_mul_pd(_mm256_add_pd(nx, one), _mm256_set1_pd(sx)));
    _mm256_storeu_pd(out.y, _mm256_mul_pd(_mm256_add_pd(ny, one), _mm256_set1_pd(sy)));
    _mm256_storeu_pd(out.z, _mm256_add_pd(_mm256_mul_pd(nz, half), half));
    if (_mm256_movemask_pd(_mm256_cmp_pd(c[3], b[3], _CMP_NGT_UQ)) != 0) {
        out.window = out.depth = std::numeric_limits<double>::infinity();
        return true;
    }
    const __m256d w = _mm256_sub_pd(c[3], b[3]);
    const __m256d ex = _mm256_div_pd(_mm256_mul_pd(_mm256_set1_pd(sx),
                                                   _mm256_add_pd(b[0], _mm256_mul_pd(_mm256_andnot_pd(sign, nx), b[3]))), w);
    const __m256d ey = _mm256_div_pd(_mm256_mul_pd(_mm256_set1_pd(sy),
                                                   _mm256_add_pd(b[1], _mm256_mul_pd(_mm256_andnot_pd(sign, ny), b[3]))), w);
    const __m256d ez = _mm256_div_pd(_mm256_mul_pd(half, _mm256_add_pd(b[2], _mm256_mul_pd(_mm256_andnot_pd(sign, nz), b[3]))), w);
    // The largest lane (every lane finite here).
    const auto largest_lane = [](__m256d v) {
        const __m128d m = _mm_max_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
        return _mm_cvtsd_f64(_mm_max_sd(m, _mm_unpackhi_pd(m, m)));
    };
    out.window = largest_lane(_mm256_max_pd(ex, ey));
    out.depth = largest_lane(ez);
    return true;
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

bool tile_pixels_behind_avx2(const OccludeeEdges &p, const float *tile, int x8, int y8, int c0, int c1, int r0,
                             int r1)
{
    const __m256d zero = _mm256_setzero_pd();
    const __m256d za = _mm256_set1_pd(p.za), zb = _mm256_set1_pd(p.zb), zc = _mm256_set1_pd(p.zc);
    const __m256d floor_z = _mm256_set1_pd(p.floor_z);
    const __m128i lane = _mm_setr_epi32(0, 1, 2, 3);
    // The row's two halves of four columns, and which of their lanes lie in
    // [c0, c1).
    for (int half = c0 / 4 * 4; half < c1; half += 4) {
        const __m128i column = _mm_add_epi32(lane, _mm_set1_epi32(half));
        const __m256d chosen = _mm256_castsi256_pd(_mm256_cvtepi32_epi64(
            _mm_and_si128(_mm_cmpgt_epi32(column, _mm_set1_epi32(c0 - 1)), _mm_cmpgt_epi32(_mm_set1_epi32(c1), column))));
        const __m256d x = _mm256_cvtepi32_pd(_mm_add_epi32(column, _mm_set1_epi32(x8)));
        __m256d ex[4];
        for (int e = 0; e < p.edges; ++e)
            ex[e] = _mm256_mul_pd(_mm256_set1_pd(p.ea[e]), x);
        const __m256d zx = _mm256_mul_pd(za, x);
        for (int r = r0; r < r1; ++r) {
            const __m256d y = _mm256_set1_pd(double(y8 + r));
            __m256d reached = chosen;
            for (int e = 0; e < p.edges; ++e) {
                const __m256d value = _mm256_add_pd(_mm256_add_pd(ex[e], _mm256_mul_pd(_mm256_set1_pd(p.eb[e]), y)),
                                                    _mm256_set1_pd(p.ec[e]));
                reached = _mm256_and_pd(reached, _mm256_cmp_pd(value, zero, _CMP_GE_OQ));
            }
            // max_pd(plane, floor) is floor where the plane is not above it
            // (NaN included), as std::max(floor, plane).
            const __m256d nearest = _mm256_max_pd(_mm256_add_pd(_mm256_add_pd(zx, _mm256_mul_pd(zb, y)), zc), floor_z);
            const __m256d depth = _mm256_cvtps_pd(_mm_loadu_ps(tile + r * tile_size + half));
            if (_mm256_movemask_pd(_mm256_and_pd(reached, _mm256_cmp_pd(depth, nearest, _CMP_NLT_UQ))) != 0)
                return false;
        }
    }
    return true;
}

}  // namespace occu::raster
