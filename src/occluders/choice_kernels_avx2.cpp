// SPDX-License-Identifier: MIT
// The choice's lanes in AVX2 (occluders/choice_kernels.h): the expressions
// of choice_kernels_scalar.cpp, eight triangles to an instruction.
#include <immintrin.h>

#include <cmath>

#include "occluders/choice_kernels.h"

namespace occu::choice {

void score_lanes_avx2(const TriangleLanes &t, const std::uint32_t *gather, std::uint32_t first, int count,
                      const ChoiceView &view, unsigned planes, LaneScores &out)
{
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256i in_count = _mm256_cmpgt_epi32(_mm256_set1_epi32(count), lane);
    // A slot's float in field f: its block's, f's row, its lane.
    __m256i index = _mm256_setzero_si256();
    const float *block = t.blocks + first / 8 * block_floats;
    if (gather) {
        const __m256i slot = _mm256_maskload_epi32(reinterpret_cast<const int *>(gather), in_count);
        index = _mm256_add_epi32(_mm256_mullo_epi32(_mm256_srli_epi32(slot, 3), _mm256_set1_epi32(int(block_floats))),
                                 _mm256_and_si256(slot, _mm256_set1_epi32(7)));
        block = t.blocks;
    }
    const auto load = [&](int field) {
        if (!gather)
            return _mm256_loadu_ps(block + field * 8);
        return _mm256_mask_i32gather_ps(_mm256_setzero_ps(), block + field * 8, index, _mm256_castsi256_ps(in_count), 4);
    };
    __m256 p[3][3];
    for (int v = 0; v < 3; ++v)
        for (int axis = 0; axis < 3; ++axis)
            p[v][axis] = load(corner0_x + 3 * v + axis);
    const __m256 facing = _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(load(normal_x), _mm256_sub_ps(_mm256_set1_ps(view.eye.x), p[0][0])),
                      _mm256_mul_ps(load(normal_x + 1), _mm256_sub_ps(_mm256_set1_ps(view.eye.y), p[0][1]))),
        _mm256_mul_ps(load(normal_x + 2), _mm256_sub_ps(_mm256_set1_ps(view.eye.z), p[0][2])));
    const __m256 wx = _mm256_set1_ps(view.w_row.x), wy = _mm256_set1_ps(view.w_row.y),
                 wz = _mm256_set1_ps(view.w_row.z), ww = _mm256_set1_ps(view.w_row.w);
    __m256 w[3];
    for (int v = 0; v < 3; ++v)
        w[v] = _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(wx, p[v][0]), _mm256_mul_ps(wy, p[v][1])),
                                           _mm256_mul_ps(wz, p[v][2])),
                             ww);
    const __m256 most = _mm256_mul_ps(_mm256_set1_ps(view.area_scale), facing);
    const __m256 nearest_w = _mm256_min_ps(_mm256_min_ps(w[0], w[1]), w[2]);
    const __m256 near = _mm256_set1_ps(view.near), zero = _mm256_setzero_ps();
    const __m256 beyond = _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(w[0], near, _CMP_GT_OQ), _mm256_cmp_ps(w[1], near, _CMP_GT_OQ)),
                                        _mm256_cmp_ps(w[2], near, _CMP_GT_OQ));
    // Beyond the near plane: twice the projected area. Across it: twice
    // the world area over the nearest corner's squared w, at least the
    // near distance.
    const __m256 projected = _mm256_div_ps(most, _mm256_mul_ps(_mm256_mul_ps(w[0], w[1]), w[2]));
    const __m256 nearest = _mm256_max_ps(near, nearest_w);
    const __m256 solid = _mm256_div_ps(load(twice_area), _mm256_mul_ps(nearest, nearest));
    const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7FFFFFFF));
    const __m256 solid_kept = _mm256_and_ps(_mm256_cmp_ps(facing, zero, _CMP_GT_OQ),
                                            _mm256_cmp_ps(_mm256_and_ps(solid, abs_mask),
                                                          _mm256_set1_ps(__builtin_inff()), _CMP_LT_OQ));
    const __m256 score = _mm256_blendv_ps(solid, projected, beyond);
    __m256 keep = _mm256_blendv_ps(solid_kept, _mm256_cmp_ps(projected, zero, _CMP_GT_OQ), beyond);
    keep = _mm256_and_ps(keep, _mm256_castsi256_ps(in_count));
    for (unsigned j = 0; j < 6; ++j) {
        if (!(planes & (1u << j)))
            continue;
        const glm::vec4 &q = view.planes[j];
        const __m256 qx = _mm256_set1_ps(q.x), qy = _mm256_set1_ps(q.y), qz = _mm256_set1_ps(q.z),
                     qw = _mm256_set1_ps(q.w);
        __m256 behind = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
        for (int v = 0; v < 3; ++v) {
            const __m256 d = _mm256_add_ps(
                _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(qx, p[v][0]), _mm256_mul_ps(qy, p[v][1])), _mm256_mul_ps(qz, p[v][2])),
                qw);
            behind = _mm256_and_ps(behind, _mm256_cmp_ps(d, zero, _CMP_LT_OQ));
        }
        keep = _mm256_andnot_ps(behind, keep);
    }
    _mm256_storeu_ps(out.score, _mm256_and_ps(score, _mm256_castsi256_ps(in_count)));
    _mm256_storeu_ps(out.most, _mm256_and_ps(most, _mm256_castsi256_ps(in_count)));
    _mm256_storeu_ps(out.nearest_w, _mm256_and_ps(nearest_w, _mm256_castsi256_ps(in_count)));
    out.keep = unsigned(_mm256_movemask_ps(keep));
}

void bound_boxes_avx2(const BoxArrays &b, std::uint32_t first, int count, const ChoiceView &view, unsigned planes,
                      LaneBounds &out)
{
    const __m256i in_count = _mm256_cmpgt_epi32(_mm256_set1_epi32(count), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    __m256 lo[3], hi[3];
    for (int axis = 0; axis < 3; ++axis) {
        lo[axis] = _mm256_loadu_ps(b.min[axis] + first);
        hi[axis] = _mm256_loadu_ps(b.max[axis] + first);
    }
    // std::min(a, b) is _mm256_min_ps(b, a), std::max(a, b) _mm256_max_ps(b, a).
    __m256 nearest_w = _mm256_set1_ps(view.w_row.w);
    for (int axis = 0; axis < 3; ++axis) {
        const __m256 m = _mm256_set1_ps(view.w_row[axis]);
        nearest_w = _mm256_add_ps(nearest_w, _mm256_min_ps(_mm256_mul_ps(m, hi[axis]), _mm256_mul_ps(m, lo[axis])));
    }
    const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7FFFFFFF));
    __m256 far_squared = _mm256_setzero_ps();
    for (int axis = 0; axis < 3; ++axis) {
        const __m256 e = _mm256_set1_ps(view.eye[axis]);
        const __m256 d = _mm256_max_ps(_mm256_and_ps(_mm256_sub_ps(hi[axis], e), abs_mask),
                                       _mm256_and_ps(_mm256_sub_ps(e, lo[axis]), abs_mask));
        far_squared = _mm256_add_ps(far_squared, _mm256_mul_ps(d, d));
    }
    const __m256 scale = _mm256_mul_ps(_mm256_set1_ps(std::fabs(view.area_scale)), _mm256_sqrt_ps(far_squared));
    const float near = view.near;
    const __m256 near_lanes = _mm256_set1_ps(near);
    const __m256 projected = _mm256_div_ps(scale, _mm256_mul_ps(_mm256_mul_ps(nearest_w, nearest_w), nearest_w));
    const __m256 across_near = _mm256_max_ps(_mm256_set1_ps(1.0f / (near * near)),
                                             _mm256_div_ps(scale, _mm256_set1_ps(near * near * near)));
    const __m256 per_area = _mm256_blendv_ps(across_near, projected, _mm256_cmp_ps(nearest_w, near_lanes, _CMP_GT_OQ));
    _mm256_storeu_ps(out.per_area, _mm256_and_ps(per_area, _mm256_castsi256_ps(in_count)));
    _mm256_storeu_ps(out.nearest_w, _mm256_and_ps(nearest_w, _mm256_castsi256_ps(in_count)));
    // The planes as Frustum::classify tests them, eight boxes a plane (only
    // those in `planes`: the others are masked off in the end anyway), each
    // box's planes behind and across as bits of its lane.
    const __m256 zero = _mm256_setzero_ps();
    __m256i behind = _mm256_setzero_si256(), across = _mm256_setzero_si256();
    for (unsigned left = planes & 0x3Fu; left != 0; left &= left - 1) {
        const int j = __builtin_ctz(left);
        const glm::vec4 &q = view.planes[j];
        __m256 far = _mm256_setzero_ps(), near_sum = _mm256_setzero_ps();
        for (int axis = 0; axis < 3; ++axis) {
            const __m256 n = _mm256_set1_ps(q[axis]);
            const bool positive = q[axis] >= 0.0f;
            const __m256 f = _mm256_mul_ps(n, positive ? hi[axis] : lo[axis]);
            const __m256 c = _mm256_mul_ps(n, positive ? lo[axis] : hi[axis]);
            far = axis == 0 ? f : _mm256_add_ps(far, f);
            near_sum = axis == 0 ? c : _mm256_add_ps(near_sum, c);
        }
        far = _mm256_add_ps(far, _mm256_set1_ps(q.w));
        near_sum = _mm256_add_ps(near_sum, _mm256_set1_ps(q.w));
        const __m256i bit = _mm256_set1_epi32(1 << j);
        behind = _mm256_or_si256(behind, _mm256_and_si256(_mm256_castps_si256(_mm256_cmp_ps(far, zero, _CMP_LT_OQ)), bit));
        across = _mm256_or_si256(across, _mm256_and_si256(_mm256_castps_si256(_mm256_cmp_ps(near_sum, zero, _CMP_LT_OQ)), bit));
    }
    // The planes crossed before the first behind: behind's lowest bit less
    // one masks them (all ones where none is behind).
    const __m256i lowest = _mm256_and_si256(behind, _mm256_sub_epi32(_mm256_setzero_si256(), behind));
    const __m256i crossing =
        _mm256_and_si256(across, _mm256_sub_epi32(lowest, _mm256_set1_epi32(1)));
    _mm256_storeu_si256(reinterpret_cast<__m256i *>(out.crossing), _mm256_and_si256(crossing, in_count));
    const __m256i outside = _mm256_and_si256(_mm256_cmpgt_epi32(behind, _mm256_setzero_si256()), in_count);
    out.outside = unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(outside)));
}

}  // namespace occu::choice
