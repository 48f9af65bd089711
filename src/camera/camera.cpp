// SPDX-License-Identifier: MIT
#include "camera/camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <emmintrin.h>

#include <algorithm>
#include <cmath>

namespace occu {

glm::mat4 Camera::view() const
{
    // lookAt builds the camera's x axis as normalize(cross(forward, up)),
    // which is NaN when up is parallel to the view direction (the default
    // up, +y, looking straight down or up). Then the up vector becomes the
    // world axis least aligned with the view direction, preferring -z (a
    // view straight down shows -z at the top, as a map shows north).
    const glm::vec3 forward = glm::normalize(target - position);
    glm::vec3 up_vector = up;
    if (glm::length(glm::cross(forward, glm::normalize(up))) < 1e-3f) {
        const glm::vec3 axes[3] = {{0.0f, 0.0f, -1.0f}, {0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
        up_vector = axes[0];
        for (const glm::vec3 &axis : axes)
            if (std::fabs(glm::dot(axis, forward)) < std::fabs(glm::dot(up_vector, forward)))
                up_vector = axis;
    }
    return glm::lookAt(position, target, up_vector);
}

glm::mat4 Camera::projection() const
{
    return glm::perspective(glm::radians(fovy_degrees), aspect, near_plane, far_plane);
}

std::optional<BoxProjection> project_box(const glm::mat4 &view_projection, const glm::vec3 &eye, const Aabb &box)
{
    if (box.contains(eye))
        return std::nullopt;
    // The eight corners (Aabb::corner's order) four at a time in SSE2 lanes
    // (x86-64's baseline), each lane glm's float product for one corner in
    // glm's order, (m0 x + m1 y) + (m2 z + m3), with no fused operation:
    // every lane equals what glm computes, bit for bit. Every occlusion
    // test projects every node it tests, so this is on every strategy's path.
    const glm::mat4 &m = view_projection;
    const __m128 x = _mm_setr_ps(box.min.x, box.max.x, box.min.x, box.max.x);
    const __m128 y = _mm_setr_ps(box.min.y, box.min.y, box.max.y, box.max.y);
    const __m128 negate = _mm_set1_ps(-0.0f), zero = _mm_setzero_ps();
    alignas(16) float ndc_x[8], ndc_y[8], ndc_z[8];
    int behind = 0;
    for (int half = 0; half < 2; ++half) {
        const __m128 z = _mm_set1_ps(half ? box.max.z : box.min.z);
        __m128 row[4];
        for (int r = 0; r < 4; ++r)
            row[r] = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(m[0][r]), x), _mm_mul_ps(_mm_set1_ps(m[1][r]), y)),
                                _mm_add_ps(_mm_mul_ps(_mm_set1_ps(m[2][r]), z), _mm_set1_ps(m[3][r])));
        // c.w <= 0 or c.z < -c.w: behind the eye or in front of the near plane.
        behind |= _mm_movemask_ps(_mm_or_ps(_mm_cmple_ps(row[3], zero), _mm_cmplt_ps(row[2], _mm_xor_ps(row[3], negate))));
        _mm_store_ps(ndc_x + 4 * half, _mm_div_ps(row[0], row[3]));
        _mm_store_ps(ndc_y + 4 * half, _mm_div_ps(row[1], row[3]));
        _mm_store_ps(ndc_z + 4 * half, _mm_div_ps(row[2], row[3]));
    }
    if (behind)
        return std::nullopt;
    // Folded corner by corner as glm::min, glm::max and std::min fold them
    // (a NaN corner leaves the bounds as they were).
    BoxProjection p{glm::vec2(1e30f), glm::vec2(-1e30f), 1.0f};
    for (int i = 0; i < 8; ++i) {
        const glm::vec2 ndc(ndc_x[i], ndc_y[i]);
        p.ndc_min = glm::min(p.ndc_min, ndc);
        p.ndc_max = glm::max(p.ndc_max, ndc);
        p.window_z_near = std::min(p.window_z_near, 0.5f * ndc_z[i] + 0.5f);
    }
    return p;
}

Frustum::Frustum(const glm::mat4 &m)
{
    // Row i of the matrix is (m[0][i], m[1][i], m[2][i], m[3][i]) in GLM's
    // column-major storage; a point p is inside when -w <= x, y, z <= w.
    auto row = [&m](int i) { return glm::vec4(m[0][i], m[1][i], m[2][i], m[3][i]); };
    const glm::vec4 w = row(3);
    planes_ = {w + row(0), w - row(0), w + row(1), w - row(1), w + row(2), w - row(2)};
    for (std::size_t i = 0; i < planes_.size(); ++i) {
        glm::vec4 &p = planes_[i];
        p /= glm::length(glm::vec3(p));
        lane_x_[i] = p.x;
        lane_y_[i] = p.y;
        lane_z_[i] = p.z;
        lane_w_[i] = p.w;
    }
}

Frustum::Side Frustum::classify(const Aabb &box) const
{
    unsigned crossing = all_planes;
    return classify(box, crossing);
}

Frustum::Side Frustum::classify(const Aabb &box, unsigned &crossing) const
{
    // Four planes a step in SSE2 lanes: for each, the box's corner farthest
    // along its normal (behind it: the box is outside) and the nearest
    // (behind it: the box reaches across), glm::dot's order
    // (n.x c.x + n.y c.y) + n.z c.z, then + w. The answer is that of the
    // planes in order: the first in `crossing` with the box behind it
    // decides outside, and the planes crossed before it are reported.
    const __m128 zero = _mm_setzero_ps();
    const __m128 lo_x = _mm_set1_ps(box.min.x), lo_y = _mm_set1_ps(box.min.y), lo_z = _mm_set1_ps(box.min.z);
    const __m128 hi_x = _mm_set1_ps(box.max.x), hi_y = _mm_set1_ps(box.max.y), hi_z = _mm_set1_ps(box.max.z);
    const auto select = [](__m128 mask, __m128 a, __m128 b) {
        return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b));
    };
    unsigned behind = 0, across = 0;
    for (int g = 0; g < 8; g += 4) {
        const __m128 nx = _mm_load_ps(lane_x_ + g), ny = _mm_load_ps(lane_y_ + g), nz = _mm_load_ps(lane_z_ + g),
                     nw = _mm_load_ps(lane_w_ + g);
        const __m128 px = _mm_cmpge_ps(nx, zero), py = _mm_cmpge_ps(ny, zero), pz = _mm_cmpge_ps(nz, zero);
        const __m128 far = _mm_add_ps(
            _mm_add_ps(_mm_add_ps(_mm_mul_ps(nx, select(px, hi_x, lo_x)), _mm_mul_ps(ny, select(py, hi_y, lo_y))),
                       _mm_mul_ps(nz, select(pz, hi_z, lo_z))),
            nw);
        const __m128 near = _mm_add_ps(
            _mm_add_ps(_mm_add_ps(_mm_mul_ps(nx, select(px, lo_x, hi_x)), _mm_mul_ps(ny, select(py, lo_y, hi_y))),
                       _mm_mul_ps(nz, select(pz, lo_z, hi_z))),
            nw);
        behind |= unsigned(_mm_movemask_ps(_mm_cmplt_ps(far, zero))) << g;
        across |= unsigned(_mm_movemask_ps(_mm_cmplt_ps(near, zero))) << g;
    }
    const unsigned planes = crossing & all_planes;
    behind &= planes;
    across &= planes;
    if (behind) {
        crossing = across & ((behind & (~behind + 1u)) - 1u);   // the planes before the first behind
        return Side::outside;
    }
    crossing = across;
    return across ? Side::intersecting : Side::inside;
}

}  // namespace occu
