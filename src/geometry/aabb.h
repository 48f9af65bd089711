// SPDX-License-Identifier: MIT
// Axis-aligned bounding boxes.
//
// Conventions for all of occu's geometry: right-handed world space, y up,
// lengths in metres; a box is empty when min > max on any axis.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <limits>

namespace occu {

struct Aabb {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{std::numeric_limits<float>::lowest()};

    static Aabb of(const glm::vec3 &a, const glm::vec3 &b) { return Aabb{glm::min(a, b), glm::max(a, b)}; }

    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 extent() const { return max - min; }

    void expand(const glm::vec3 &p)
    {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void expand(const Aabb &b)
    {
        if (b.empty())
            return;
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }
    bool contains(const glm::vec3 &p) const
    {
        return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y && p.z >= min.z && p.z <= max.z;
    }
    bool overlaps(const Aabb &b) const
    {
        return min.x <= b.max.x && b.min.x <= max.x && min.y <= b.max.y && b.min.y <= max.y && min.z <= b.max.z &&
               b.min.z <= max.z;
    }
    // The eight corners, bit i of the index choosing max on axis i.
    glm::vec3 corner(int i) const
    {
        return {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z};
    }
};

// A box's six faces as corner indices (Aabb::corner), each counter-clockwise
// seen from outside, in the order -x, +x, -y, +y, -z, +z.
inline constexpr int aabb_faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};

}  // namespace occu
