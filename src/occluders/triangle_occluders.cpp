// SPDX-License-Identifier: MIT
// The scene's own triangles as occluders: see triangle_occluders.h.
#include "occluders/triangle_occluders.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace occu {

TriangleOccluders::TriangleOccluders(const Scene &scene, const Settings &settings, std::size_t least_budget,
                                     const Hierarchy *hierarchy)
    : hierarchy_(hierarchy), budget_(least_budget)
{
    if (settings.knows("occluder-triangles"))
        budget_ = std::max(budget_, std::size_t(settings.integer("occluder-triangles")));
    if (budget_ == 0)
        return;
    // The groups: each leaf's occluder triangles (the hierarchy puts them
    // first), or every occluder mesh's in one. A see-through mesh hides
    // nothing (Mesh::occluder).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> refs;   // mesh, first index
    const auto add_group = [&](const Aabb &bounds) {
        Group g;
        g.bounds = bounds;
        g.first = std::uint32_t(corners_.size() / 3);
        std::vector<std::pair<float, std::size_t>> order;
        for (std::size_t i = 0; i < refs.size(); ++i) {
            const Mesh &mesh = scene.meshes[refs[i].first];
            const std::uint32_t *idx = mesh.indices.data() + refs[i].second;
            const glm::vec3 &a = mesh.positions[idx[0]], &b = mesh.positions[idx[1]], &c = mesh.positions[idx[2]];
            const float twice = glm::length(glm::cross(b - a, c - a));
            order.emplace_back(std::isfinite(twice) ? twice : 0.0f, i);
        }
        std::stable_sort(order.begin(), order.end(), std::greater<>());
        for (const auto &[twice, i] : order) {
            const Mesh &mesh = scene.meshes[refs[i].first];
            const std::uint32_t *idx = mesh.indices.data() + refs[i].second;
            for (int v = 0; v < 3; ++v)
                corners_.push_back(mesh.positions[idx[v]]);
            twice_area_.push_back(twice);
        }
        g.count = std::uint32_t(order.size());
        g.largest = order.empty() ? 0.0f : order.front().first;
        if (g.count > 0)
            groups_.push_back(g);
        refs.clear();
        return g.count > 0;
    };
    if (hierarchy) {
        leaf_group_.assign(hierarchy->nodes().size(), ~0u);
        for (std::size_t n = 0; n < hierarchy->nodes().size(); ++n) {
            const HierarchyNode &node = hierarchy->nodes()[n];
            if (!node.leaf())
                continue;
            for (std::uint32_t i = node.first_triangle; i < node.first_triangle + node.occluder_triangles; ++i)
                refs.emplace_back(hierarchy->triangles()[i].mesh, hierarchy->triangles()[i].first_index);
            if (add_group(node.bounds))
                leaf_group_[n] = std::uint32_t(groups_.size() - 1);
        }
    } else {
        for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
            if (!scene.meshes[m].occluder)
                continue;
            for (std::size_t t = 0; t + 2 < scene.meshes[m].indices.size(); t += 3)
                refs.emplace_back(std::uint32_t(m), std::uint32_t(t));
        }
        add_group(scene.bounds);
    }
    // With merged coverage, the triangle across each edge (GL draws a
    // sample on a shared edge with one of the two), among the occluder
    // triangles of every mesh: equal positions are transformed alike.
    if (settings.knows("coverage") && settings.text("coverage") == "merged")
        across_ = shared_edge_opposites(corners_);
}

bool TriangleOccluders::score(std::uint32_t t, const glm::mat4 &vp, const Frame &frame, float &out) const
{
    // The projected area in normalized device coordinates, signed (front
    // faces counter-clockwise, positive): back faces and triangles wholly
    // outside one clip plane are never chosen. A triangle across the near
    // plane has no such area; it is scored by its world area over its
    // nearest vertex's squared depth (at least the near distance), the
    // solid angle it would subtend, and the rasterizer clips it.
    const float near = std::max(frame.camera.near_plane, 1e-6f);
    const glm::vec3 *p = corners_.data() + 3 * std::size_t(t);
    glm::vec4 c[3];
    for (int v = 0; v < 3; ++v)
        c[v] = vp * glm::vec4(p[v], 1.0f);
    for (int axis = 0; axis < 3; ++axis)
        if ((c[0][axis] > c[0].w && c[1][axis] > c[1].w && c[2][axis] > c[2].w) ||
            (c[0][axis] < -c[0].w && c[1][axis] < -c[1].w && c[2][axis] < -c[2].w))
            return false;
    if (c[0].w > near && c[1].w > near && c[2].w > near) {
        const glm::vec2 a(c[0] / c[0].w), b(c[1] / c[1].w), d(c[2] / c[2].w);
        const glm::vec2 e = b - a, f = d - a;
        out = e.x * f.y - e.y * f.x;
        return out > 0.0f;   // false: back-facing, degenerate, or NaN
    }
    const glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
    if (!(glm::dot(n, frame.camera.position - p[0]) > 0.0f))
        return false;   // seen from behind: GL culls it
    const float w = std::max(near, std::min({c[0].w, c[1].w, c[2].w}));
    out = glm::length(n) / (w * w);
    return std::isfinite(out);
}

std::size_t TriangleOccluders::render(const Frame &frame, DepthRasterizer &raster)
{
    const std::vector<std::uint32_t> &indices = choose(frame);
    const std::size_t count = indices.size() / 3;
    if (count == 0)
        return 0;
    drawn_across_.clear();
    if (!across_.empty())
        for (std::uint32_t i : indices)
            drawn_across_.push_back(across_[i]);
    raster.render_triangles(corners_.data(), indices.data(), count, across_.empty() ? nullptr : drawn_across_.data());
    return count;
}

const std::vector<std::uint32_t> &TriangleOccluders::choose(const Frame &frame)
{
    const std::size_t limit = budget_;
    chosen_.clear();
    drawn_indices_.clear();
    if (limit == 0 || groups_.empty())
        return drawn_indices_;
    const glm::mat4 &vp = frame.view_projection;
    const float near = std::max(frame.camera.near_plane, 1e-6f);
    // The most a triangle of a group may score: twice its world area
    // times the projection's scale (P00 P11, bounding how NDC areas grow
    // with 1 / w^2; twice for the slant of a point off the view axis) over
    // the group's nearest view depth squared, at least the near distance.
    // Only the order of visits hangs on it.
    const float scale = 2.0f * std::max(1.0f, std::abs(vp[0][0] * vp[1][1]));
    const auto nearest_w = [&](const Aabb &b) {
        float w = vp[3][3];
        for (int axis = 0; axis < 3; ++axis)
            w += std::min(vp[axis][3] * b.min[axis], vp[axis][3] * b.max[axis]);
        return std::max(near, w);
    };
    groups_by_bound_.clear();
    if (hierarchy_) {
        for (std::uint32_t leaf : leaves_in_frustum(*hierarchy_, Frustum(vp))) {
            const std::uint32_t g = leaf_group_[leaf];
            if (g == ~0u)
                continue;
            const float w = nearest_w(groups_[g].bounds);
            groups_by_bound_.emplace_back(groups_[g].largest * scale / (w * w), g);
        }
    } else {
        groups_by_bound_.emplace_back(std::numeric_limits<float>::infinity(), 0u);
    }
    std::sort(groups_by_bound_.begin(), groups_by_bound_.end(), std::greater<>());
    // The best `limit` scores in a min-heap: its top, once full, is the
    // score to beat.
    const auto smaller_first = [](const auto &a, const auto &b) { return a.first > b.first; };
    for (const auto &[bound, g] : groups_by_bound_) {
        if (chosen_.size() == limit && !(bound > chosen_.front().first))
            break;
        const Group &group = groups_[g];
        const float w = nearest_w(group.bounds);
        const float per_area = scale / (w * w);
        for (std::uint32_t t = group.first; t < group.first + group.count; ++t) {
            if (chosen_.size() == limit && !(twice_area_[t] * per_area > chosen_.front().first))
                break;
            float s;
            if (!score(t, vp, frame, s))
                continue;
            if (chosen_.size() < limit) {
                chosen_.emplace_back(s, t);
                std::push_heap(chosen_.begin(), chosen_.end(), smaller_first);
            } else if (s > chosen_.front().first) {
                std::pop_heap(chosen_.begin(), chosen_.end(), smaller_first);
                chosen_.back() = {s, t};
                std::push_heap(chosen_.begin(), chosen_.end(), smaller_first);
            }
        }
    }
    // Nearest first (by the nearest vertex's clip w), as a z-buffer fills.
    for (auto &c : chosen_) {
        float w = std::numeric_limits<float>::max();
        for (int v = 0; v < 3; ++v)
            w = std::min(w, (vp * glm::vec4(corners_[3 * std::size_t(c.second) + std::size_t(v)], 1.0f)).w);
        c.first = w;
    }
    std::sort(chosen_.begin(), chosen_.end());
    for (const auto &c : chosen_)
        for (std::uint32_t v = 0; v < 3; ++v)
            drawn_indices_.push_back(3 * c.second + v);
    return drawn_indices_;
}

}  // namespace occu
