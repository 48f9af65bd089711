#include "render/id_buffer.h"

#include "culling/traversal.h"

namespace occu {

std::vector<std::uint32_t> render_leaf_ids(const SceneRenderer &renderer, const Camera &camera,
                                           const std::vector<std::uint32_t> &leaves, int width, int height)
{
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    glPushAttrib(GL_ENABLE_BIT | GL_COLOR_BUFFER_BIT | GL_SCISSOR_BIT);
    glViewport(0, 0, width, height);
    glDisable(GL_DITHER);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_TEST);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    load_camera(camera);
    for (std::uint32_t n : leaves) {
        const std::uint32_t id = n + 1;
        glColor3ub(GLubyte(id & 0xff), GLubyte((id >> 8) & 0xff), GLubyte((id >> 16) & 0xff));
        renderer.draw_leaf_flat(n);
    }
    std::vector<std::uint8_t> pixels(std::size_t(width) * std::size_t(height) * 4);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    glPopAttrib();
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);

    std::vector<std::uint32_t> ids(std::size_t(width) * std::size_t(height));
    for (std::size_t i = 0; i < ids.size(); ++i)
        ids[i] = pixels[4 * i] | pixels[4 * i + 1] << 8 | pixels[4 * i + 2] << 16;
    return ids;
}

}  // namespace occu
