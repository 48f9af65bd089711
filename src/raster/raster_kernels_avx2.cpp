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
    __m256 ea[max_edges];
    for (int e = 0; e < s.edges; ++e)
        ea[e] = _mm256_set1_ps(s.ea[e]);
    Band band;
    for (int y8 = s.y0 / tile_size * tile_size; y8 < s.y1; y8 += tile_size) {
        band_terms(s, y8 > s.y0 ? y8 : s.y0, y8 + tile_size < s.y1 ? y8 + tile_size : s.y1, &band);
        const bool all_rows = band.row0 == y8 && band.row1 == y8 + tile_size;
        for (int x8 = s.x0 / tile_size * tile_size; x8 < s.x1; x8 += tile_size) {
            const Cover cover = tile_cover(s, band, x8);
            if (cover == Cover::none)
                continue;
            const std::size_t t = tile_index(buffer, x8, y8);
            if (tile_nearest_depth(s, band, x8) >= buffer.farthest_bound[t])
                continue;
            float *tile = tile_at(buffer, t);
            // float(x8 + lane), exactly, as the scalar loop converts it.
            const __m256 fx = _mm256_add_ps(_mm256_set1_ps(float(x8)), lanes);
            const __m256 z_column = _mm256_mul_ps(za, fx);
            if (cover == Cover::whole) {
                // std::min(z, zcap) is (zcap < z ? zcap : z), which
                // min_ps(zcap, z) is; keeping z where z < old is min_ps(z, old).
                for (int y = band.row0; y < band.row1; ++y) {
                    float *row = tile + (y - y8) * tile_size;
                    const __m256 z =
                        _mm256_min_ps(zcap, _mm256_add_ps(z_column, _mm256_set1_ps(band.depth_term[y - y8])));
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
            for (int y = band.row0; y < band.row1; ++y) {
                const float *edge_term = band.edge_term[y - y8];
                __m256 inside = _mm256_cmp_ps(_mm256_add_ps(_mm256_mul_ps(ea[0], fx), _mm256_set1_ps(edge_term[0])),
                                              zero, _CMP_GE_OQ);
                for (int e = 1; e < s.edges; ++e)
                    inside = _mm256_and_ps(inside, _mm256_cmp_ps(_mm256_add_ps(_mm256_mul_ps(ea[e], fx),
                                                                               _mm256_set1_ps(edge_term[e])),
                                                                 zero, _CMP_GE_OQ));
                if (_mm256_movemask_ps(inside) == 0)
                    continue;
                const __m256 z =
                    _mm256_min_ps(zcap, _mm256_add_ps(z_column, _mm256_set1_ps(band.depth_term[y - y8])));
                float *row = tile + (y - y8) * tile_size;
                const __m256 old = _mm256_loadu_ps(row);
                const __m256 write = _mm256_and_ps(inside, _mm256_cmp_ps(z, old, _CMP_LT_OQ));
                _mm256_storeu_ps(row, _mm256_blendv_ps(old, z, write));
                wrote = _mm256_or_ps(wrote, write);
            }
            if (_mm256_movemask_ps(wrote) != 0)
                buffer.dirty[t] = 1;
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
