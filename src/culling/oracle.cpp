#include "culling/oracle.h"

#include <algorithm>

#include "render/id_buffer.h"

namespace occu {

VisibilityTruth exact_visibility(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera,
                                 int width, int height)
{
    VisibilityTruth truth;
    const Frustum frustum(camera.view_projection());
    const auto &nodes = hierarchy.nodes();
    for (std::uint32_t n = 0; n < nodes.size(); ++n)
        if (nodes[n].leaf() && frustum.classify(nodes[n].bounds) != Frustum::Side::outside)
            truth.in_frustum.push_back(n);

    std::vector<bool> seen(nodes.size() + 1, false);
    for (std::uint32_t id : render_leaf_ids(renderer, camera, truth.in_frustum, width, height))
        if (id && id <= nodes.size())
            seen[id] = true;
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
