// SPDX-License-Identifier: MIT
#include "spatial/inside_points.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace occu {

namespace {

std::array<glm::vec3, inside_ray_directions> make_directions()
{
    std::array<glm::vec3, inside_ray_directions> d{};
    int n = 0;
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {1.0f, -1.0f}) {
            glm::vec3 v(0.0f);
            v[axis] = sign;
            d[std::size_t(n++)] = v;
        }
    for (int corner = 0; corner < 8; ++corner)
        d[std::size_t(n++)] = glm::normalize(glm::vec3((corner & 1) ? 1.0f : -1.0f, (corner & 2) ? 1.0f : -1.0f,
                                                       (corner & 4) ? 1.0f : -1.0f));
    return d;
}

const std::array<glm::vec3, inside_ray_directions> directions = make_directions();

// The slab test: whether the ray meets `box` at a distance >= 0.
// `inverse` is 1 / direction per axis (infinite along an axis the ray
// runs parallel to: then the origin must lie within that slab).
bool ray_meets_box(const Aabb &box, const glm::vec3 &origin, const glm::vec3 &direction, const glm::vec3 &inverse)
{
    float near = 0.0f, far = std::numeric_limits<float>::max();
    for (int axis = 0; axis < 3; ++axis) {
        if (direction[axis] == 0.0f) {
            if (origin[axis] < box.min[axis] || origin[axis] > box.max[axis])
                return false;
            continue;
        }
        float t0 = (box.min[axis] - origin[axis]) * inverse[axis];
        float t1 = (box.max[axis] - origin[axis]) * inverse[axis];
        if (t0 > t1)
            std::swap(t0, t1);
        near = std::max(near, t0);
        far = std::min(far, t1);
        if (near > far)
            return false;
    }
    return true;
}

// Moeller and Trumbore's ray-triangle test ("Fast, minimum storage
// ray/triangle intersection", 1997), either face: a hit at t > 0.
bool ray_hits_triangle(const glm::vec3 &origin, const glm::vec3 &direction, const glm::vec3 &a, const glm::vec3 &b,
                       const glm::vec3 &c)
{
    const glm::vec3 e1 = b - a, e2 = c - a;
    const glm::vec3 p = glm::cross(direction, e2);
    const float det = glm::dot(e1, p);
    if (std::fabs(det) < 1e-12f)
        return false;
    const float inv = 1.0f / det;
    const glm::vec3 s = origin - a;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f)
        return false;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(direction, q) * inv;
    if (v < 0.0f || u + v > 1.0f)
        return false;
    return glm::dot(e2, q) * inv > 0.0f;
}

}  // namespace

const glm::vec3 &inside_ray_direction(int i)
{
    return directions[std::size_t(i)];
}

bool ray_hits_model(const Scene &scene, const Hierarchy &hierarchy, const glm::vec3 &origin,
                    const glm::vec3 &direction)
{
    const auto &nodes = hierarchy.nodes();
    if (nodes.empty())
        return false;
    const glm::vec3 inverse = 1.0f / direction;
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty()) {
        const HierarchyNode &node = nodes[stack.back()];
        stack.pop_back();
        if (!ray_meets_box(node.bounds, origin, direction, inverse))
            continue;
        for (std::uint32_t i = 0; i < node.child_count; ++i)
            stack.push_back(node.first_child + i);
        for (std::uint32_t i = 0; i < node.triangle_count; ++i) {
            const TriangleRef &t = hierarchy.triangles()[node.first_triangle + i];
            const Mesh &mesh = scene.meshes[t.mesh];
            const glm::vec3 &a = mesh.positions[mesh.indices[t.first_index]];
            const glm::vec3 &b = mesh.positions[mesh.indices[t.first_index + 1]];
            const glm::vec3 &c = mesh.positions[mesh.indices[t.first_index + 2]];
            if (ray_hits_triangle(origin, direction, a, b, c))
                return true;
        }
    }
    return false;
}

bool inside_model(const Scene &scene, const Hierarchy &hierarchy, const glm::vec3 &point)
{
    for (int i = 0; i < inside_ray_directions; ++i)
        if (!ray_hits_model(scene, hierarchy, point, directions[std::size_t(i)]))
            return false;
    return true;
}

}  // namespace occu
