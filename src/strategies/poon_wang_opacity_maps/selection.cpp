// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/selection.h"

#include <algorithm>


namespace occu {

namespace {

// The `limit` best of (score, node) pairs, lowest score first.
std::vector<std::uint32_t> best(std::vector<std::pair<float, std::uint32_t>> &candidates, std::size_t limit)
{
    const std::size_t count = std::min(limit, candidates.size());
    std::partial_sort(candidates.begin(), candidates.begin() + std::ptrdiff_t(count), candidates.end());
    std::vector<std::uint32_t> out(count);
    for (std::size_t i = 0; i < count; ++i)
        out[i] = candidates[i].second;
    return out;
}

}  // namespace

std::vector<std::uint32_t> occluders_by_projected_size(const Hierarchy &hierarchy, const Camera &camera,
                                                       const Frustum &frustum, std::size_t limit)
{
    std::vector<std::pair<float, std::uint32_t>> candidates;
    for (std::uint32_t n : leaves_in_frustum(hierarchy, frustum)) {
        if (hierarchy.nodes()[n].occluder_triangles == 0)
            continue;   // see-through alone: it would draw no occluder
        const Aabb &b = hierarchy.nodes()[n].bounds;
        const glm::vec3 e = b.extent();
        const glm::vec3 nearest = glm::clamp(camera.position, b.min, b.max);
        const float d2 = std::max(glm::dot(nearest - camera.position, nearest - camera.position), 1e-4f);
        candidates.push_back({-glm::dot(e, e) / d2, n});
    }
    return best(candidates, limit);
}

std::vector<std::uint32_t> occluders_by_first_hit(IdBuffer &ids, const Hierarchy &hierarchy, const Camera &camera,
                                                  const Frustum &frustum, int width, int height, std::size_t limit)
{
    const auto leaves = leaves_in_frustum(hierarchy, frustum);
    const auto pixels = pixels_per_leaf(ids.render(camera, leaves, width, height), hierarchy.nodes().size());
    std::vector<std::pair<float, std::uint32_t>> candidates;
    for (std::uint32_t n : leaves)
        if (pixels[n])
            candidates.push_back({-float(pixels[n]), n});
    return best(candidates, limit);
}

std::vector<std::uint32_t> first_leaves_within_triangles(const std::vector<std::uint32_t> &best_first,
                                                         const std::vector<std::uint32_t> &triangles,
                                                         std::size_t budget)
{
    std::vector<std::uint32_t> out;
    std::size_t taken = 0;
    for (std::uint32_t n : best_first) {
        if (taken >= budget && !out.empty())
            break;
        out.push_back(n);
        taken += n < triangles.size() ? triangles[n] : 0;
    }
    return out;
}

}  // namespace occu
