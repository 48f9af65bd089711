#include "render/top_view.h"

#include <algorithm>

#include "gl/gl_headers.h"

namespace occu {

void render_top_view(const Hierarchy &hierarchy, const Camera &camera, const std::vector<std::uint32_t> &drawn_in)
{
    std::vector<std::uint32_t> drawn = drawn_in;
    std::sort(drawn.begin(), drawn.end());
    const Aabb &b = hierarchy.root().bounds;
    const float margin = 0.05f * std::max(b.extent().x, b.extent().z);

    glPushAttrib(GL_ENABLE_BIT | GL_COLOR_BUFFER_BIT);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    // x to the right, z downwards, as a map of the xz plane.
    glOrtho(b.min.x - margin, b.max.x + margin, b.max.z + margin, b.min.z - margin, -1, 1);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();

    const Frustum frustum(camera.view_projection());
    const auto &nodes = hierarchy.nodes();
    glBegin(GL_QUADS);
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
        if (!nodes[n].leaf() || nodes[n].bounds.extent().x > 0.5f * b.extent().x)
            continue;   // the ground would cover everything
        if (std::binary_search(drawn.begin(), drawn.end(), n))
            glColor3f(0.2f, 0.7f, 0.25f);
        else if (frustum.classify(nodes[n].bounds) == Frustum::Side::outside)
            glColor3f(0.45f, 0.45f, 0.45f);
        else
            glColor3f(0.95f, 0.85f, 0.1f);
        const Aabb &a = nodes[n].bounds;
        glVertex2f(a.min.x, a.min.z);
        glVertex2f(a.max.x, a.min.z);
        glVertex2f(a.max.x, a.max.z);
        glVertex2f(a.min.x, a.max.z);
    }
    glEnd();

    // The camera: a dot and its view direction.
    const glm::vec3 p = camera.position, d = glm::normalize(camera.target - camera.position);
    const float len = 0.08f * std::max(b.extent().x, b.extent().z);
    glColor3f(0.9f, 0.1f, 0.1f);
    glPointSize(7.0f);
    glBegin(GL_POINTS);
    glVertex2f(p.x, p.z);
    glEnd();
    glLineWidth(2.0f);
    glBegin(GL_LINES);
    glVertex2f(p.x, p.z);
    glVertex2f(p.x + d.x * len, p.z + d.z * len);
    glEnd();
    glPopAttrib();
}

}  // namespace occu
