// SPDX-License-Identifier: MIT
#include "strategies/leone_occluder_skins/triangle_clusters.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace occu {

TriangleClusters::TriangleClusters(const Scene &scene, const Hierarchy &hierarchy)
{
    const auto &triangles = hierarchy.triangles();
    const auto &nodes = hierarchy.nodes();
    order_.resize(triangles.size());
    first_cluster_.assign(nodes.size() + 1, 0);
    std::vector<float> area(triangles.size());
    std::vector<glm::vec3> centre(triangles.size());
    std::vector<Aabb> bounds(triangles.size());
    for (std::uint32_t i = 0; i < triangles.size(); ++i) {
        const Mesh &mesh = scene.meshes[triangles[i].mesh];
        const std::uint32_t *idx = mesh.indices.data() + triangles[i].first_index;
        const glm::vec3 &a = mesh.positions[idx[0]], &b = mesh.positions[idx[1]], &c = mesh.positions[idx[2]];
        const float twice = glm::length(glm::cross(b - a, c - a));
        area[i] = std::isfinite(twice) ? twice : 0.0f;
        // A triangle with a corner that is not finite sorts last, boxless.
        centre[i] = glm::vec3(std::numeric_limits<float>::infinity());
        if (std::isfinite(a.x + a.y + a.z + b.x + b.y + b.z + c.x + c.y + c.z)) {
            centre[i] = (a + b + c) / 3.0f;
            bounds[i] = Aabb::of(a, b);
            bounds[i].expand(c);
        }
        order_[i] = i;
    }
    const auto split = [&](auto &self, std::uint32_t leaf_first, std::uint32_t begin, std::uint32_t end) -> void {
        const auto b = order_.begin() + begin, e = order_.begin() + end;
        if (end - begin > cluster_triangles) {
            Aabb spread;
            for (auto i = b; i != e; ++i)
                if (!bounds[*i].empty())
                    spread.expand(centre[*i]);
            const glm::vec3 size = spread.empty() ? glm::vec3(0.0f) : spread.extent();
            const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
            const std::uint32_t middle = begin + (end - begin) / 2;
            std::nth_element(b, order_.begin() + middle, e, [&](std::uint32_t x, std::uint32_t y) {
                return centre[x][axis] < centre[y][axis];
            });
            self(self, leaf_first, begin, middle);
            self(self, leaf_first, middle, end);
            return;
        }
        std::stable_sort(b, e, [&](std::uint32_t x, std::uint32_t y) { return area[x] > area[y]; });
        Cluster cluster{{}, begin - leaf_first, end - begin};
        bool finite = true;
        for (auto i = b; i != e; ++i) {
            finite = finite && !bounds[*i].empty();
            cluster.box.expand(bounds[*i]);
        }
        if (!finite)
            cluster.box = Aabb{};
        clusters_.push_back(cluster);
    };
    for (std::uint32_t node = 0; node < nodes.size(); ++node) {
        first_cluster_[node] = std::uint32_t(clusters_.size());
        const HierarchyNode &n = nodes[node];
        if (n.leaf() && n.triangle_count > 0)
            split(split, n.first_triangle, n.first_triangle, n.first_triangle + n.triangle_count);
    }
    first_cluster_[nodes.size()] = std::uint32_t(clusters_.size());
    // Each slot's corners, in slot order.
    corners_.resize(3 * triangles.size());
    for (std::size_t s = 0; s < order_.size(); ++s) {
        const TriangleRef &t = triangles[order_[s]];
        const Mesh &mesh = scene.meshes[t.mesh];
        const std::uint32_t *index = mesh.indices.data() + t.first_index;
        for (std::size_t c = 0; c < 3; ++c)
            corners_[3 * s + c] = mesh.positions[index[c]];
    }
}

}  // namespace occu
