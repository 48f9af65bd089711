// SPDX-License-Identifier: MIT
// The scene's own triangles as occluders: see triangle_occluders.h.
#include "occluders/triangle_occluders.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace occu {

TriangleOccluders::TriangleOccluders(const Scene &scene, const Settings &settings, std::size_t least_budget)
    : scene_(&scene), budget_(least_budget)
{
    if (settings.knows("occluder-triangles"))
        budget_ = std::max(budget_, std::size_t(settings.integer("occluder-triangles")));
    if (budget_ == 0)
        return;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        // A see-through mesh hides nothing (Mesh::occluder).
        if (!scene.meshes[m].occluder)
            continue;
        for (std::size_t t = 0; t + 2 < scene.meshes[m].indices.size(); t += 3)
            triangles_.emplace_back(std::uint32_t(m), std::uint32_t(t));
    }
    // With merged coverage, the triangle across each edge (GL draws a
    // sample on a shared edge with one of the two), among the occluder
    // triangles of every mesh: equal positions are transformed alike.
    if (settings.knows("coverage") && settings.text("coverage") == "merged") {
        std::vector<glm::vec3> corners;
        corners.reserve(3 * triangles_.size());
        for (const auto &[m, first] : triangles_)
            for (int v = 0; v < 3; ++v)
                corners.push_back(scene.meshes[m].positions[scene.meshes[m].indices[first + std::uint32_t(v)]]);
        across_ = shared_edge_opposites(corners);
    }
}

std::size_t TriangleOccluders::render(const Frame &frame, DepthRasterizer &raster)
{
    const std::size_t limit = budget_;
    chosen_triangles_.clear();
    if (limit == 0 || triangles_.empty())
        return 0;
    // The projected area in normalized device coordinates, signed (front
    // faces counter-clockwise, positive): back faces and triangles wholly
    // outside one clip plane are never chosen. A triangle across the near
    // plane has no such area; it is scored by its world area over its
    // nearest vertex's squared depth (at least the near distance), the
    // solid angle it would subtend, and the rasterizer clips it.
    const glm::mat4 &vp = frame.view_projection;
    const float near = std::max(frame.camera.near_plane, 1e-6f);
    const Scene &scene = *scene_;
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
        const Mesh &mesh = scene.meshes[triangles_[i].first];
        const std::uint32_t *idx = mesh.indices.data() + triangles_[i].second;
        glm::vec4 c[3];
        for (int v = 0; v < 3; ++v)
            c[v] = vp * glm::vec4(mesh.positions[idx[v]], 1.0f);
        bool outside = false;
        for (int axis = 0; axis < 3 && !outside; ++axis)
            outside = (c[0][axis] > c[0].w && c[1][axis] > c[1].w && c[2][axis] > c[2].w) ||
                      (c[0][axis] < -c[0].w && c[1][axis] < -c[1].w && c[2][axis] < -c[2].w);
        if (outside)
            continue;
        float score;
        if (c[0].w > near && c[1].w > near && c[2].w > near) {
            const glm::vec2 a(c[0] / c[0].w), b(c[1] / c[1].w), d(c[2] / c[2].w);
            const glm::vec2 e = b - a, f = d - a;
            score = e.x * f.y - e.y * f.x;
            if (!(score > 0.0f))
                continue;   // back-facing, degenerate, or NaN
        } else {
            const glm::vec3 &p0 = mesh.positions[idx[0]], &p1 = mesh.positions[idx[1]], &p2 = mesh.positions[idx[2]];
            const glm::vec3 eye = frame.camera.position;
            const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
            if (!(glm::dot(n, eye - p0) > 0.0f))
                continue;   // seen from behind: GL culls it
            const float w = std::max(near, std::min({c[0].w, c[1].w, c[2].w}));
            score = glm::length(n) / (w * w);
            if (!std::isfinite(score))
                continue;
        }
        chosen_triangles_.emplace_back(score, std::uint32_t(i));
    }
    if (chosen_triangles_.size() > limit) {
        std::nth_element(chosen_triangles_.begin(), chosen_triangles_.begin() + std::ptrdiff_t(limit),
                         chosen_triangles_.end(), [](const auto &a, const auto &b) { return a.first > b.first; });
        chosen_triangles_.resize(limit);
    }
    // Nearest first (by the nearest vertex's clip w), as a z-buffer fills.
    for (auto &c : chosen_triangles_) {
        const Mesh &mesh = scene.meshes[triangles_[c.second].first];
        const std::uint32_t *idx = mesh.indices.data() + triangles_[c.second].second;
        float w = std::numeric_limits<float>::max();
        for (int v = 0; v < 3; ++v)
            w = std::min(w, (vp * glm::vec4(mesh.positions[idx[v]], 1.0f)).w);
        c.first = w;
    }
    std::sort(chosen_triangles_.begin(), chosen_triangles_.end());
    for (const auto &c : chosen_triangles_) {
        const Mesh &mesh = scene.meshes[triangles_[c.second].first];
        raster.render_triangles(mesh.positions.data(), mesh.indices.data() + triangles_[c.second].second, 1,
                                across_.empty() ? nullptr : across_.data() + 3 * std::size_t(c.second));
    }
    return chosen_triangles_.size();
}

}  // namespace occu
