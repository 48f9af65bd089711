// The AVX2 loops: eight depth pixels of a tile row at once, the scalar
// loops' expressions lane by lane (raster_kernels_scalar.cpp).
#include "raster/raster_kernels.h"

#include <immintrin.h>

namespace occu::raster {

void fill_avx2(const PolygonSetup &s, const TileBuffer &buffer)
{
    const __m256 lanes = _mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256 zero = _mm256_setzero_ps();
    const __m256 za = _mm256_set1_ps(s.za), zcap = _mm256_set1_ps(s.zcap);
    __m256 ea[max_edges], row_term[max_edges];
    for (int e = 0; e < s.edges; ++e)
        ea[e] = _mm256_set1_ps(s.ea[e]);
    for (int y = s.y0; y < s.y1; ++y) {
        int xl, xr;
        row_span(s, y, buffer.padded_width, &xl, &xr);
        if (xl >= xr)
            continue;
        const float fy = float(y);
        for (int e = 0; e < s.edges; ++e)
            row_term[e] = _mm256_set1_ps(s.eb[e] * fy + s.ec[e]);
        const __m256 z_row = _mm256_set1_ps(s.zb * fy + s.zc);
        for (int x8 = xl; x8 < xr; x8 += tile_size) {
            // float(x8 + lane), exactly, as the scalar loop converts it.
            const __m256 fx = _mm256_add_ps(_mm256_set1_ps(float(x8)), lanes);
            __m256 inside = _mm256_cmp_ps(_mm256_add_ps(_mm256_mul_ps(ea[0], fx), row_term[0]), zero, _CMP_GE_OQ);
            for (int e = 1; e < s.edges; ++e)
                inside = _mm256_and_ps(
                    inside, _mm256_cmp_ps(_mm256_add_ps(_mm256_mul_ps(ea[e], fx), row_term[e]), zero, _CMP_GE_OQ));
            if (_mm256_movemask_ps(inside) == 0)
                continue;
            // std::min(z, zcap) is (zcap < z ? zcap : z), which min_ps(zcap, z) is.
            const __m256 z = _mm256_min_ps(zcap, _mm256_add_ps(_mm256_mul_ps(za, fx), z_row));
            float *row = tile_row(buffer, x8, y);
            const __m256 old = _mm256_loadu_ps(row);
            const __m256 write = _mm256_and_ps(inside, _mm256_cmp_ps(z, old, _CMP_LT_OQ));
            if (_mm256_movemask_ps(write) == 0)
                continue;
            _mm256_storeu_ps(row, _mm256_blendv_ps(old, z, write));
            tile_dirty(buffer, x8, y) = 1;
        }
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
