// SPDX-License-Identifier: MIT
// The choice's lanes in scalar code (occluders/choice_kernels.h); the AVX2
// twin is choice_kernels_avx2.cpp.
#include "occluders/choice_kernels.h"

#include <cmath>
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

}  // namespace occu::choice
