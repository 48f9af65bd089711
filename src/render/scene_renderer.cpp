#include "render/scene_renderer.h"

#include <stdexcept>

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
                prelit_rgba8(i < mesh.colors.size() ? mesh.colors[i] : mesh.color, mesh.normals[i], v.color);
                vertices.push_back(v);
            }
        }
        GenBuffers(1, &buffers_[n]);
        BindBuffer_(GL_ARRAY_BUFFER, buffers_[n]);
        BufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(Vertex)), vertices.data(), GL_STATIC_DRAW);
        vertex_counts_[n] = GLsizei(vertices.size());
    }
    BindBuffer_(GL_ARRAY_BUFFER, 0);
}

SceneRenderer::~SceneRenderer()
{
    for (GLuint b : buffers_)
        if (b)
            DeleteBuffers_(1, &b);
}

std::uint32_t SceneRenderer::draw_leaf(std::uint32_t node) const
{
    if (!buffers_[node])
        return 0;
    BindBuffer_(GL_ARRAY_BUFFER, buffers_[node]);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(3, GL_FLOAT, sizeof(Vertex), reinterpret_cast<const void *>(offsetof(Vertex, position)));
    glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(Vertex), reinterpret_cast<const void *>(offsetof(Vertex, color)));
    glDrawArrays(GL_TRIANGLES, 0, vertex_counts_[node]);
    glDisableClientState(GL_COLOR_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
    BindBuffer_(GL_ARRAY_BUFFER, 0);
    return std::uint32_t(vertex_counts_[node] / 3);
}

void SceneRenderer::draw_leaf_flat(std::uint32_t node) const
{
    if (!buffers_[node])
        return;
    BindBuffer_(GL_ARRAY_BUFFER, buffers_[node]);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, sizeof(Vertex), reinterpret_cast<const void *>(offsetof(Vertex, position)));
    glDrawArrays(GL_TRIANGLES, 0, vertex_counts_[node]);
    glDisableClientState(GL_VERTEX_ARRAY);
    BindBuffer_(GL_ARRAY_BUFFER, 0);
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
