// SPDX-License-Identifier: MIT
#include "evaluation/lost_pixels.h"

#include <cstring>

#include "gl/gl_headers.h"
#include "gl/state.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"

namespace occu {

std::uint64_t lost_pixels(const std::uint8_t *reference, const std::uint8_t *culled, std::size_t pixel_count)
{
    std::uint64_t lost = 0;
    for (std::size_t i = 0; i < pixel_count; ++i)
        lost += std::memcmp(reference + 4 * i, culled + 4 * i, 4) != 0;
    return lost;
}

void draw_unculled_after(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera,
                         const std::vector<std::uint32_t> &first)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl::load_camera(camera);
    const auto &nodes = hierarchy.nodes();
    std::vector<std::uint8_t> done(nodes.size(), 0);
    for (std::uint32_t leaf : first) {
        renderer.draw_leaf(leaf);
        done[leaf] = 1;
    }
    std::vector<std::uint32_t> leaves = first;
    for (std::uint32_t n = 0; n < nodes.size(); ++n)
        if (nodes[n].leaf() && !done[n]) {
            renderer.draw_leaf(n);
            leaves.push_back(n);
        }
    renderer.draw_see_through(leaves, camera.position);
    glFinish();
}

PixelLoss count_lost_pixels(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera,
                            const std::vector<std::uint32_t> &drawn, const std::uint8_t *unculled,
                            const std::uint8_t *frame, std::size_t pixel_count)
{
    const std::uint64_t differing = unculled ? lost_pixels(unculled, frame, pixel_count) : 0;
    if (unculled && differing == 0)
        return {};
    const std::vector<std::uint8_t> culled(frame, frame + 4 * pixel_count);
    draw_unculled_after(renderer, hierarchy, camera, drawn);
    PixelLoss loss;
    loss.lost = lost_pixels(frame, culled.data(), pixel_count);
    loss.tied = differing > loss.lost ? differing - loss.lost : 0;
    return loss;
}

}  // namespace occu
