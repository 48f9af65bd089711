// SPDX-License-Identifier: MIT
// box_footprint's AVX2 kernel (camera/footprint.h): box_footprint_scalar's
// float expressions, the eight corners one a lane. Built with -mavx2 and
// -ffp-contract=off (no fused multiply-add, as the scalar kernel has none),
// called only where the CPU has AVX2.
#include "camera/footprint.h"

#include <immintrin.h>

#include <limits>

namespace occu {

namespace {

// The scalar kernel folds the corners in order from a first value,
// keeping a corner where it is strictly below what it holds (glm::min,
// (b < a) ? b : a; std::min likewise): the earliest of the least, and a
// NaN corner never kept. The same answer as a tree: with the NaN lanes
// first made +inf (never below the first value, which is finite), keeping
// the earlier of two equal halves ((later < earlier) ? later : earlier,
// min_ps(later, earlier)) keeps the earliest of the least of their union,
// so halves may be joined in any grouping that keeps their order: lanes
// (0, 1), (2, 3), ..., then pairs of those, then the two sets of four,
// then the first value before them all. (Only +0 and -0 are equal with
// other bits; which of them comes out is what a different order would
// change.)
float earliest_least(__m256 v, float first)
{
    v = _mm256_min_ps(v, _mm256_set1_ps(std::numeric_limits<float>::infinity()));   // NaN: +inf
    v = _mm256_min_ps(_mm256_movehdup_ps(v), v);                                     // lane 2k+1 after 2k
    v = _mm256_min_ps(_mm256_permute_ps(v, _MM_SHUFFLE(2, 2, 2, 2)), v);             // lanes 2, 3 after 0, 1
    const __m128 all = _mm_min_ss(_mm256_extractf128_ps(v, 1), _mm256_castps256_ps128(v));   // 4-7 after 0-3
    return _mm_cvtss_f32(_mm_min_ss(all, _mm_set_ss(first)));
}

// The same for glm::max's (a < b) ? b : a: NaN lanes -inf, and
// max_ps(later, earlier), which keeps the earlier unless the later is
// strictly above it.
float earliest_greatest(__m256 v, float first)
{
    v = _mm256_max_ps(v, _mm256_set1_ps(-std::numeric_limits<float>::infinity()));   // NaN: -inf
    v = _mm256_max_ps(_mm256_movehdup_ps(v), v);
    v = _mm256_max_ps(_mm256_permute_ps(v, _MM_SHUFFLE(2, 2, 2, 2)), v);
    const __m128 all = _mm_max_ss(_mm256_extractf128_ps(v, 1), _mm256_castps256_ps128(v));
    return _mm_cvtss_f32(_mm_max_ss(all, _mm_set_ss(first)));
}

}  // namespace

std::optional<Footprint> box_footprint_avx2(const glm::mat4 &view_projection, const glm::vec3 &eye, const Aabb &box,
                                            int viewport_width, int viewport_height)
{
    // The corners in Aabb::corner's order, corner i in lane i: project_box's
    // float products per lane, (m0 x + m1 y) + (m2 z + m3).
    const glm::mat4 &m = view_projection;
    const __m256 x = _mm256_setr_ps(box.min.x, box.max.x, box.min.x, box.max.x, box.min.x, box.max.x, box.min.x, box.max.x);
    const __m256 y = _mm256_setr_ps(box.min.y, box.min.y, box.max.y, box.max.y, box.min.y, box.min.y, box.max.y, box.max.y);
    const __m256 z = _mm256_setr_ps(box.min.z, box.min.z, box.min.z, box.min.z, box.max.z, box.max.z, box.max.z, box.max.z);
    // The six bounds finite: v - v is 0 for a finite v, NaN for infinity
    // or NaN, and a sum of zeros is 0.
    const __m256 differences = _mm256_add_ps(_mm256_add_ps(_mm256_sub_ps(x, x), _mm256_sub_ps(y, y)), _mm256_sub_ps(z, z));
    if (_mm256_movemask_ps(_mm256_cmp_ps(differences, differences, _CMP_UNORD_Q)) != 0)
        return std::nullopt;
    if (box.contains(eye))
        return std::nullopt;
    __m256 row[4];
    for (int r = 0; r < 4; ++r)
        row[r] = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(m[0][r]), x), _mm256_mul_ps(_mm256_set1_ps(m[1][r]), y)),
                               _mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(m[2][r]), z), _mm256_set1_ps(m[3][r])));
    // c.w <= 0 or c.z < -c.w: behind the eye or in front of the near plane.
    const __m256 behind = _mm256_or_ps(_mm256_cmp_ps(row[3], _mm256_setzero_ps(), _CMP_LE_OQ),
                                       _mm256_cmp_ps(row[2], _mm256_xor_ps(row[3], _mm256_set1_ps(-0.0f)), _CMP_LT_OQ));
    if (_mm256_movemask_ps(behind) != 0)
        return std::nullopt;
    const __m256 ndc_x = _mm256_div_ps(row[0], row[3]), ndc_y = _mm256_div_ps(row[1], row[3]);
    const __m256 half = _mm256_set1_ps(0.5f);
    const __m256 window_z = _mm256_add_ps(_mm256_mul_ps(half, _mm256_div_ps(row[2], row[3])), half);
    // Bounds x, y low, x, y high, as the scalar's BoxProjection.
    const __m128 bounds = _mm_setr_ps(earliest_least(ndc_x, 1e30f), earliest_least(ndc_y, 1e30f),
                                      earliest_greatest(ndc_x, -1e30f), earliest_greatest(ndc_y, -1e30f));
    const float z_near = earliest_least(window_z, 1.0f);
    // A non-finite projection: no footprint. Subtracting a finite value
    // from itself gives 0; infinity or NaN give NaN.
    const __m128 zero = _mm_setzero_ps();
    if (_mm_movemask_ps(_mm_cmpunord_ps(_mm_sub_ps(bounds, bounds), zero)) != 0 || !(z_near - z_near == 0.0f))
        return std::nullopt;
    // NDC to window x, y ((ndc + 1) 0.5 size), clamped to [-2, size + 2]
    // (std::clamp, as max then min: no NaN here), floor below, ceil above.
    const float width = float(viewport_width), height = float(viewport_height);
    const __m128 size = _mm_setr_ps(width, height, width, height);
    const __m128 window = _mm_mul_ps(_mm_mul_ps(_mm_add_ps(bounds, _mm_set1_ps(1.0f)), _mm_set1_ps(0.5f)), size);
    const __m128 clamped =
        _mm_min_ps(_mm_max_ps(window, _mm_set1_ps(-2.0f)), _mm_add_ps(size, _mm_set1_ps(2.0f)));
    const __m128 rounded = _mm_blend_ps(_mm_round_ps(clamped, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC),
                                        _mm_round_ps(clamped, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC), 0xC);
    alignas(16) int grown[4];
    _mm_store_si128(reinterpret_cast<__m128i *>(grown),
                    _mm_add_epi32(_mm_cvttps_epi32(rounded), _mm_setr_epi32(-1, -1, 1, 1)));
    return Footprint{PixelRect{grown[0], grown[1], grown[2], grown[3]}.clamped({0, 0, viewport_width, viewport_height}),
                     z_near};
}

}  // namespace occu
