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
    for (glm::vec4 &p : planes_)
        p /= glm::length(glm::vec3(p));
}

Frustum::Side Frustum::classify(const Aabb &box) const
{
    unsigned crossing = all_planes;
    return classify(box, crossing);
}

Frustum::Side Frustum::classify(const Aabb &box, unsigned &crossing) const
{
    Side side = Side::inside;
    const unsigned planes = crossing;
    crossing = 0;
    for (unsigned i = 0; i < planes_.size(); ++i) {
        if (!(planes & (1u << i)))
            continue;
        const glm::vec4 &p = planes_[i];
        const glm::vec3 n(p);
        // The corner farthest along the normal, and the nearest.
        const glm::vec3 far_corner{n.x >= 0 ? box.max.x : box.min.x, n.y >= 0 ? box.max.y : box.min.y,
                                   n.z >= 0 ? box.max.z : box.min.z};
        const glm::vec3 near_corner{n.x >= 0 ? box.min.x : box.max.x, n.y >= 0 ? box.min.y : box.max.y,
                                    n.z >= 0 ? box.min.z : box.max.z};
        if (glm::dot(n, far_corner) + p.w < 0.0f)
            return Side::outside;
        if (glm::dot(n, near_corner) + p.w < 0.0f) {
            side = Side::intersecting;
            crossing |= 1u << i;
        }
    }
    return side;
}

}  // namespace occu
