// SPDX-License-Identifier: MIT
#include "render/scene_renderer.h"

#include <algorithm>
#include <stdexcept>

#include "gl/state.h"
#include "render/shading.h"

namespace occu {

namespace {
struct Vertex {
    float position[3];
    std::uint8_t color[4];
};
}  // namespace

SceneRenderer::SceneRenderer(const Scene &scene, const Hierarchy &hierarchy) : hierarchy_(hierarchy)
{
    auto GenBuffers = reinterpret_cast<PFNGLGENBUFFERSPROC>(gl::get_proc_address("glGenBuffers"));
    auto BufferData = reinterpret_cast<PFNGLBUFFERDATAPROC>(gl::get_proc_address("glBufferData"));
    BindBuffer_ = reinterpret_cast<PFNGLBINDBUFFERPROC>(gl::get_proc_address("glBindBuffer"));
    DeleteBuffers_ = reinterpret_cast<PFNGLDELETEBUFFERSPROC>(gl::get_proc_address("glDeleteBuffers"));
    if (!GenBuffers || !BufferData || !BindBuffer_ || !DeleteBuffers_)
        throw std::runtime_error("SceneRenderer needs vertex buffer objects (GL 1.5)");

    const auto &nodes = hierarchy.nodes();
    buffers_.assign(nodes.size(), 0);
    vertex_counts_.assign(nodes.size(), 0);
    see_through_counts_.assign(nodes.size(), 0);
    std::vector<Vertex> vertices;
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
        if (!nodes[n].leaf() || nodes[n].triangle_count == 0)
            continue;
        vertices.clear();
        for (std::uint32_t t = 0; t < nodes[n].triangle_count; ++t) {
            const TriangleRef &ref = hierarchy.triangles()[nodes[n].first_triangle + t];
            const Mesh &mesh = scene.meshes[ref.mesh];
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t i = mesh.indices[ref.first_index + k];
                Vertex v{{mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z}, {}};
                const glm::vec3 &colour = i < mesh.colors.size() ? mesh.colors[i] : mesh.color;
                if (mesh.shaded)
                    prelit_rgba8(colour, mesh.normals[i], v.color);
                else
                    unlit_rgba8(colour, v.color);
                if (!mesh.occluder)
                    v.color[3] = see_through_alpha;
                vertices.push_back(v);
            }
        }
        GenBuffers(1, &buffers_[n]);
        BindBuffer_(GL_ARRAY_BUFFER, buffers_[n]);
        BufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(Vertex)), vertices.data(), GL_STATIC_DRAW);
        vertex_counts_[n] = GLsizei(vertices.size());
        // The hierarchy puts a leaf's occluders first (spatial/hierarchy.h).
        see_through_counts_[n] = GLsizei(3 * (nodes[n].triangle_count - nodes[n].occluder_triangles));
        any_see_through_ = any_see_through_ || see_through_counts_[n] > 0;
    }
    BindBuffer_(GL_ARRAY_BUFFER, 0);
}

SceneRenderer::~SceneRenderer()
{
    for (GLuint b : buffers_)
        if (b)
            DeleteBuffers_(1, &b);
}

namespace {

// The first vertex and the vertex count of `part` in a leaf of `total`
// vertices whose last `see_through` are see-through.
std::pair<GLint, GLsizei> part_range(LeafPart part, GLsizei total, GLsizei see_through)
{
    switch (part) {
    case LeafPart::occluders: return {0, total - see_through};
    case LeafPart::see_through: return {total - see_through, see_through};
    case LeafPart::all: break;
    }
    return {0, total};
}

}  // namespace

std::uint32_t SceneRenderer::draw_leaf(std::uint32_t node, LeafPart part) const
{
    const auto [first, count] = part_range(part, vertex_counts_[node], see_through_counts_[node]);
    if (!buffers_[node] || count == 0)
        return 0;
    BindBuffer_(GL_ARRAY_BUFFER, buffers_[node]);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(3, GL_FLOAT, sizeof(Vertex), reinterpret_cast<const void *>(offsetof(Vertex, position)));
    glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(Vertex), reinterpret_cast<const void *>(offsetof(Vertex, color)));
    glDrawArrays(GL_TRIANGLES, first, count);
    glDisableClientState(GL_COLOR_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
    BindBuffer_(GL_ARRAY_BUFFER, 0);
    return std::uint32_t(count / 3);
}

void SceneRenderer::draw_leaf_flat(std::uint32_t node, LeafPart part) const
{
    const auto [first, count] = part_range(part, vertex_counts_[node], see_through_counts_[node]);
    if (!buffers_[node] || count == 0)
        return;
    BindBuffer_(GL_ARRAY_BUFFER, buffers_[node]);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, sizeof(Vertex), reinterpret_cast<const void *>(offsetof(Vertex, position)));
    glDrawArrays(GL_TRIANGLES, first, count);
    glDisableClientState(GL_VERTEX_ARRAY);
    BindBuffer_(GL_ARRAY_BUFFER, 0);
}

std::uint32_t SceneRenderer::draw_see_through(const std::vector<std::uint32_t> &leaves, const glm::vec3 &eye) const
{
    if (!any_see_through_)
        return 0;
    // Farthest first, so that nearer see-through surfaces blend over
    // farther ones; the order depends on the eye and the leaves alone, so
    // a frame that drew fewer leaves draws the see-through ones it has in
    // the same order as the unculled frame.
    std::vector<std::pair<float, std::uint32_t>> order;
    for (std::uint32_t n : leaves)
        if (n < see_through_counts_.size() && see_through_counts_[n] > 0) {
            const glm::vec3 d = hierarchy_.nodes()[n].bounds.center() - eye;
            order.emplace_back(-glm::dot(d, d), n);
        }
    if (order.empty())
        return 0;
    std::sort(order.begin(), order.end());
    gl::AttribScope state(GL_ENABLE_BIT | GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    std::uint32_t triangles = 0;
    for (const auto &entry : order)
        triangles += draw_leaf(entry.second, LeafPart::see_through);
    return triangles;
}

void SceneRenderer::draw_box(const Aabb &b)
{
    glBegin(GL_QUADS);
    for (const auto &f : aabb_faces)
        for (int c : f) {
            const glm::vec3 p = b.corner(c);
            glVertex3f(p.x, p.y, p.z);
        }
    glEnd();
}

}  // namespace occu
