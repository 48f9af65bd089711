// SPDX-License-Identifier: MIT
// The choice's lanes in scalar code (occluders/choice_kernels.h); the AVX2
// twin is choice_kernels_avx2.cpp.
#include "occluders/choice_kernels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace occu::choice {

std::uint32_t TriangleArrays::start_group()
{
    slots_ = (slots_ + 7) / 8 * 8;
    return slots_;
}

void TriangleArrays::add(const glm::vec3 *corners, const glm::vec3 &normal, float twice_area)
{
    blocks_.resize((slots_ / 8 + 1) * block_floats, 0.0f);
    float *lane = &blocks_[slots_ / 8 * block_floats + slots_ % 8];
    for (int axis = 0; axis < 3; ++axis) {
        lane[(normal_x + axis) * 8] = normal[axis];
        lane[(corner0_x + axis) * 8] = corners[0][axis];
        lane[(corner1_x + axis) * 8] = corners[1][axis];
        lane[(corner2_x + axis) * 8] = corners[2][axis];
    }
    lane[Field::twice_area * 8] = twice_area;
    slot_of_.push_back(slots_++);
}

void TriangleArrays::finish()
{
    blocks_.resize((slots_ + 7) / 8 * block_floats, 0.0f);
    blocks_.shrink_to_fit();
}

namespace {

// As _mm256_min_ps and _mm256_max_ps (the second operand where either is NaN).
float lane_min(float a, float b) { return a < b ? a : b; }
float lane_max(float a, float b) { return a > b ? a : b; }

}  // namespace

void score_lanes_scalar(const TriangleLanes &t, const std::uint32_t *gather, std::uint32_t first, int count,
                        const ChoiceView &view, unsigned planes, LaneScores &out)
{
    out.keep = 0;
    for (int i = 0; i < 8; ++i) {
        out.score[i] = out.most[i] = out.nearest_w[i] = 0.0f;
        if (i >= count)
            continue;
        const std::uint32_t k = gather ? gather[i] : first + std::uint32_t(i);
        float p[3][3];
        for (int v = 0; v < 3; ++v)
            for (int axis = 0; axis < 3; ++axis)
                p[v][axis] = t.at(corner0_x + 3 * v + axis, k);
        // n . (e - p0), as glm::dot sums: (x + y) + z.
        const float facing = t.at(normal_x, k) * (view.eye.x - p[0][0]) + t.at(normal_x + 1, k) * (view.eye.y - p[0][1]) +
                             t.at(normal_x + 2, k) * (view.eye.z - p[0][2]);
        float w[3];
        for (int v = 0; v < 3; ++v)
            w[v] = view.w_row.x * p[v][0] + view.w_row.y * p[v][1] + view.w_row.z * p[v][2] + view.w_row.w;
        const float most = view.area_scale * facing;
        const float nearest_w = lane_min(lane_min(w[0], w[1]), w[2]);
        bool keep;
        float score;
        if (w[0] > view.near && w[1] > view.near && w[2] > view.near) {
            score = most / (w[0] * w[1] * w[2]);
            keep = score > 0.0f;
        } else {
            const float nearest = lane_max(view.near, nearest_w);
            score = t.at(twice_area, k) / (nearest * nearest);
            keep = facing > 0.0f && std::fabs(score) < std::numeric_limits<float>::infinity();
        }
        for (unsigned j = 0; j < 6 && keep; ++j) {
            if (!(planes & (1u << j)))
                continue;
            const glm::vec4 &q = view.planes[j];
            bool behind = true;
            for (int v = 0; v < 3; ++v)
                behind = behind && q.x * p[v][0] + q.y * p[v][1] + q.z * p[v][2] + q.w < 0.0f;
            keep = !behind;
        }
        out.score[i] = score;
        out.most[i] = most;
        out.nearest_w[i] = nearest_w;
        out.keep |= unsigned(keep) << i;
    }
}

namespace {

// The planes' answer as Frustum::classify gives it (camera/camera.cpp):
// the first tested plane with the box behind it decides outside, and the
// planes crossed before it are reported.
unsigned classified(unsigned behind, unsigned across, unsigned planes, bool &outside)
{
    behind &= planes;
    across &= planes;
    outside = behind != 0;
    return behind ? across & ((behind & (~behind + 1u)) - 1u) : across;
}

}  // namespace

void bound_boxes_scalar(const BoxArrays &b, std::uint32_t first, int count, const ChoiceView &view, unsigned planes,
                        LaneBounds &out)
{
    out.outside = 0;
    for (int i = 0; i < 8; ++i) {
        out.per_area[i] = out.nearest_w[i] = 0.0f;
        out.crossing[i] = 0;
        if (i >= count)
            continue;
        const std::uint32_t k = first + std::uint32_t(i);
        const float lo[3] = {b.min[0][k], b.min[1][k], b.min[2][k]}, hi[3] = {b.max[0][k], b.max[1][k], b.max[2][k]};
        // std::min(a, b) and std::max(a, b), as the AVX2 twin takes them:
        // b < a ? b : a, a < b ? b : a.
        float nearest_w = view.w_row.w;
        for (int axis = 0; axis < 3; ++axis) {
            const float a = view.w_row[axis] * lo[axis], c = view.w_row[axis] * hi[axis];
            nearest_w += c < a ? c : a;
        }
        float far_squared = 0.0f;
        for (int axis = 0; axis < 3; ++axis) {
            const float a = std::fabs(view.eye[axis] - lo[axis]), c = std::fabs(hi[axis] - view.eye[axis]);
            const float d = a < c ? c : a;
            far_squared += d * d;
        }
        const float scale = std::fabs(view.area_scale) * std::sqrt(far_squared);
        float per_area;
        if (nearest_w > view.near) {
            per_area = scale / (nearest_w * nearest_w * nearest_w);
        } else {
            const float beyond = scale / (view.near * view.near * view.near), across = 1.0f / (view.near * view.near);
            per_area = beyond < across ? across : beyond;
        }
        out.per_area[i] = per_area;
        out.nearest_w[i] = nearest_w;
        // Each plane's farthest corner along its normal (behind it: the
        // box is outside) and nearest (behind it: the box reaches across).
        unsigned behind = 0, across = 0;
        for (unsigned j = 0; j < 6; ++j) {
            const glm::vec4 &q = view.planes[j];
            const float far = q.x * (q.x >= 0.0f ? hi[0] : lo[0]) + q.y * (q.y >= 0.0f ? hi[1] : lo[1]) +
                              q.z * (q.z >= 0.0f ? hi[2] : lo[2]) + q.w;
            const float near = q.x * (q.x >= 0.0f ? lo[0] : hi[0]) + q.y * (q.y >= 0.0f ? lo[1] : hi[1]) +
                               q.z * (q.z >= 0.0f ? lo[2] : hi[2]) + q.w;
            behind |= unsigned(far < 0.0f) << j;
            across |= unsigned(near < 0.0f) << j;
        }
        bool outside;
        out.crossing[i] = classified(behind, across, planes, outside);
        out.outside |= unsigned(outside) << i;
    }
}

}  // namespace occu::choice
