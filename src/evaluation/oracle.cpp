// SPDX-License-Identifier: MIT
#include "evaluation/oracle.h"

#include <algorithm>

namespace occu {

VisibilityTruth Oracle::see(const Camera &camera, int width, int height)
{
    VisibilityTruth truth;
    truth.in_frustum = leaves_in_frustum(hierarchy_, Frustum(camera.view_projection()));
    const auto &nodes = hierarchy_.nodes();
    std::vector<bool> seen(nodes.size() + 1, false);
    std::vector<std::uint32_t> see_through;
    for (std::uint32_t id : ids_.render(camera, truth.in_frustum, width, height, &see_through))
        if (id && id <= nodes.size())
            seen[id] = true;
    for (std::uint32_t n : see_through)
        seen[n + 1] = true;
    for (std::uint32_t id = 1; id <= nodes.size(); ++id)
        if (seen[id])
            truth.visible.push_back(id - 1);
    return truth;
}

CullingQuality compare_with_truth(const VisibilityTruth &truth, std::vector<std::uint32_t> drawn)
{
    std::sort(drawn.begin(), drawn.end());
    auto is_drawn = [&drawn](std::uint32_t n) { return std::binary_search(drawn.begin(), drawn.end(), n); };
    CullingQuality q;
    for (std::uint32_t n : truth.in_frustum) {
        const bool visible = std::binary_search(truth.visible.begin(), truth.visible.end(), n);
        if (visible) {
            q.visible_culled += !is_drawn(n);
        } else {
            ++q.occluded;
            q.occluded_culled += !is_drawn(n);
        }
    }
    return q;
}

}  // namespace occu
