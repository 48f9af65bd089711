// SPDX-License-Identifier: MIT
#include "render/occlusion_proxy.h"

#include <algorithm>
#include <cmath>

#include "render/scene_renderer.h"

namespace occu {

ProxyTestState::ProxyTestState() : saved_(GL_ENABLE_BIT | GL_DEPTH_BUFFER_BIT | GL_POLYGON_BIT)
{
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glDepthFunc(GL_LEQUAL);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0f, -4.0f);
}

std::optional<Aabb> proxy_box(const Aabb &box, const Camera &camera, const glm::mat4 &view_projection,
                              int viewport_height)
{
    // Metres per pixel at unit distance from the eye.
    const float metres_per_pixel =
        2.0f * std::tan(glm::radians(camera.fovy_degrees) * 0.5f) / float(std::max(viewport_height, 1));
    Aabb grown = box;
    const glm::vec3 nearest = glm::clamp(camera.position, grown.min, grown.max);
    const float margin = 0.01f + 1.5f * metres_per_pixel * glm::length(nearest - camera.position);
    grown.min -= glm::vec3(margin);
    grown.max += glm::vec3(margin);
    // project_box is empty for a box that holds the eye or has a corner in
    // front of the near plane.
    if (!project_box(view_projection, camera.position, grown))
        return std::nullopt;
    return grown;
}

void draw_proxy_box(const Aabb &proxy)
{
    SceneRenderer::draw_box(proxy);
}

}  // namespace occu
