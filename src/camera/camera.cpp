// SPDX-License-Identifier: MIT
#include "camera/camera.h"

#include <glm/gtc/matrix_transform.hpp>

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
    BoxProjection p{glm::vec2(1e30f), glm::vec2(-1e30f), 1.0f};
    for (int i = 0; i < 8; ++i) {
        const glm::vec4 c = view_projection * glm::vec4(box.corner(i), 1.0f);
        if (c.w <= 0.0f || c.z < -c.w)
            return std::nullopt;
        const glm::vec2 ndc(c.x / c.w, c.y / c.w);
        p.ndc_min = glm::min(p.ndc_min, ndc);
        p.ndc_max = glm::max(p.ndc_max, ndc);
        p.window_z_near = std::min(p.window_z_near, 0.5f * (c.z / c.w) + 0.5f);
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
