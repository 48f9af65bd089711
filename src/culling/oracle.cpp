#include "culling/oracle.h"

#include <algorithm>

#include "culling/traversal.h"

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

    // IDs as colours: leaf index + 1 in 24 bits (0 is the background).
    glPushAttrib(GL_ENABLE_BIT | GL_COLOR_BUFFER_BIT);
    glDisable(GL_DITHER);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    load_camera(camera);
    for (std::uint32_t n : truth.in_frustum) {
        const std::uint32_t id = n + 1;
        glColor3ub(GLubyte(id & 0xff), GLubyte((id >> 8) & 0xff), GLubyte((id >> 16) & 0xff));
        renderer.draw_leaf_flat(n);
    }
    std::vector<std::uint8_t> pixels(std::size_t(width) * std::size_t(height) * 4);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    glPopAttrib();

    std::vector<bool> seen(nodes.size() + 1, false);
    for (std::size_t i = 0; i < pixels.size(); i += 4) {
        const std::uint32_t id = pixels[i] | pixels[i + 1] << 8 | pixels[i + 2] << 16;
        if (id && id <= nodes.size())
            seen[id] = true;
    }
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
