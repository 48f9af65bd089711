// SPDX-License-Identifier: MIT
#include "scene/level.h"

namespace occu {

std::int32_t Level::leaf_at(const glm::vec3 &p) const
{
    if (leaves.empty())
        return -1;
    if (nodes.empty())
        return 0;
    std::int32_t n = 0;
    for (;;) {
        const Node &node = nodes[std::size_t(n)];
        const Plane &plane = planes[std::size_t(node.plane)];
        const std::int32_t child = node.children[glm::dot(plane.normal, p) - plane.distance >= 0.0f ? 0 : 1];
        if (child < 0)
            return -(child + 1);
        n = child;   // after n: the reader checked, so this ends
    }
}

bool Level::cluster_sees(std::int32_t from, std::int32_t to) const
{
    if (from < 0 || to < 0 || cluster_count == 0 || from >= cluster_count || to >= cluster_count)
        return true;
    return (visibility[std::size_t(from) * std::size_t(bytes_per_cluster) + std::size_t(to) / 8] >> (to % 8)) & 1;
}

}  // namespace occu
