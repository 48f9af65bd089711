// SPDX-License-Identifier: MIT
#include "render/id_buffer.h"

#include "gl/occlusion_query.h"
#include "gl/state.h"

namespace occu {

namespace {

// Of `leaves`, those whose see-through triangles pass the depth test of the
// bound framebuffer somewhere (GL_SAMPLES_PASSED), drawn without writing
// colour or depth.
std::vector<std::uint32_t> see_through_passing(const SceneRenderer &renderer, const std::vector<std::uint32_t> &leaves)
{
    std::vector<std::uint32_t> candidates;
    for (std::uint32_t n : leaves)
        if (renderer.has_see_through(n))
            candidates.push_back(n);
    if (candidates.empty())
        return {};
    const auto gl_query = gl::QueryFunctions::load("the visibility of see-through meshes");
    std::vector<GLuint> queries(candidates.size());
    gl_query.GenQueries(GLsizei(queries.size()), queries.data());
    glDepthMask(GL_FALSE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        gl_query.BeginQuery(GL_SAMPLES_PASSED, queries[i]);
        renderer.draw_leaf_flat(candidates[i], LeafPart::see_through);
        gl_query.EndQuery(GL_SAMPLES_PASSED);
    }
    std::vector<std::uint32_t> shown;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        GLuint samples = 0;
        gl_query.GetQueryObjectuiv(queries[i], GL_QUERY_RESULT, &samples);
        if (samples)
            shown.push_back(candidates[i]);
    }
    gl_query.DeleteQueries(GLsizei(queries.size()), queries.data());
    return shown;
}

}  // namespace

std::vector<std::uint32_t> IdBuffer::render(const Camera &camera, const std::vector<std::uint32_t> &leaves, int width,
                                            int height, std::vector<std::uint32_t> *see_through_shown)
{
    std::optional<gl::Framebuffer::Bind> bind;
    if (target_kind_ == Target::own_framebuffer) {
        if (!target_)
            target_.emplace(width, height);
        target_->resize(width, height);
        bind.emplace(*target_);
    }
    std::vector<std::uint8_t> pixels(std::size_t(width) * std::size_t(height) * 4);
    {
        gl::AttribScope viewport(GL_VIEWPORT_BIT);
        glViewport(0, 0, width, height);
        gl::AttribScope state(GL_ENABLE_BIT | GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_SCISSOR_BIT |
                              GL_CURRENT_BIT);
        gl::MatrixScope matrices;
        glDisable(GL_DITHER);
        glDisable(GL_BLEND);
        glDisable(GL_SCISSOR_TEST);
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_CULL_FACE);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glClearColor(0, 0, 0, 0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gl::load_camera(camera);
        for (std::uint32_t n : leaves) {
            const std::uint32_t id = n + 1;
            glColor3ub(GLubyte(id & 0xff), GLubyte((id >> 8) & 0xff), GLubyte((id >> 16) & 0xff));
            renderer_.draw_leaf_flat(n);
        }
        glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
        if (see_through_shown)
            *see_through_shown = see_through_passing(renderer_, leaves);
    }
    std::vector<std::uint32_t> ids(std::size_t(width) * std::size_t(height));
    for (std::size_t i = 0; i < ids.size(); ++i)
        ids[i] = pixels[4 * i] | pixels[4 * i + 1] << 8 | pixels[4 * i + 2] << 16;
    return ids;
}

std::vector<std::uint32_t> pixels_per_leaf(const std::vector<std::uint32_t> &ids, std::size_t nodes)
{
    std::vector<std::uint32_t> pixels(nodes, 0);
    for (std::uint32_t id : ids)
        if (id && id <= nodes)
            ++pixels[id - 1];
    return pixels;
}

}  // namespace occu
