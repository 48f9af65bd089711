// SPDX-License-Identifier: MIT
// The occluder skins' occludee=triangles test (skins_culler.cpp) reads a
// leaf's triangles by cluster: each leaf's triangles split into clusters of
// at most cluster_triangles neighbours (halved at the median of their
// centres along the widest axis), each cluster's largest first, with the
// box of its triangles, so that one box test stands for a cluster's
// triangles where it suffices. The triangles sit in slots in that order, a
// leaf's slots at its first_triangle .. first_triangle + triangle_count,
// and each slot holds its triangle's three corners: the test reads a
// cluster's corners as one block rather than through each triangle's mesh,
// indices and positions.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/aabb.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"

namespace occu {

class TriangleClusters {
public:
    static constexpr std::uint32_t cluster_triangles = 16;

    struct Cluster {
        Aabb box;                     // empty: a corner is not finite (its triangles are tested)
        std::uint32_t first, count;   // its slots, from the leaf's first_triangle on
    };

    TriangleClusters(const Scene &scene, const Hierarchy &hierarchy);

    // The clusters of `node` (none for an inner node or an empty leaf).
    const Cluster *begin(std::uint32_t node) const { return clusters_.data() + first_cluster_[node]; }
    const Cluster *end(std::uint32_t node) const { return clusters_.data() + first_cluster_[node + 1]; }
    // The corners of the triangle in `slot`, three glm::vec3 in a row.
    const glm::vec3 *corners(std::uint32_t slot) const { return corners_.data() + 3 * std::size_t(slot); }
    // The hierarchy triangle in `slot` (Hierarchy::triangles()).
    std::uint32_t triangle(std::uint32_t slot) const { return order_[slot]; }

private:
    std::vector<std::uint32_t> order_;
    std::vector<glm::vec3> corners_;
    std::vector<Cluster> clusters_;
    std::vector<std::uint32_t> first_cluster_;
};

}  // namespace occu
