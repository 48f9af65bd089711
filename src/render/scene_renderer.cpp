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
// The same with the look's coordinates: the texture's and the lightmap atlas's.
struct TexturedVertex {
    float position[3];
    std::uint8_t color[4];
    float st[2], lightmap[2];
};

bool carries_look(const Scene &scene)
{
    return std::any_of(scene.meshes.begin(), scene.meshes.end(), [](const Mesh &m) {
        return m.texcoords.size() == m.positions.size() && !m.texcoords.empty();
    });
}

// A mesh's key in a leaf's batches: its texture, then lightmapping.
std::pair<std::int32_t, bool> batch_key(const Mesh &m) { return {m.image, m.lightmapped}; }

// The colour of vertex `i` of `mesh` in the look: white under a lightmap
// (the texture times the lightmap), else its vertex light, else flat.
void look_colour(const Mesh &mesh, std::uint32_t i, std::uint8_t rgba[4])
{
    const glm::vec3 &colour = i < mesh.colors.size() ? mesh.colors[i] : mesh.color;
    if (!mesh.shaded) {
        unlit_rgba8(colour, rgba);
    } else if (mesh.lightmapped) {
        rgba[0] = rgba[1] = rgba[2] = rgba[3] = 255;
    } else if (i < mesh.vertex_light.size()) {
        const std::uint32_t v = mesh.vertex_light[i];
        for (int k = 0; k < 3; ++k)
            rgba[k] = std::uint8_t(v >> (8 * k));
        rgba[3] = 255;
    } else {
        prelit_rgba8(colour, mesh.normals[i], rgba);
    }
}

GLuint upload(const Image &image, bool mipmaps)
{
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, mipmaps ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, mipmaps ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    // Quake III's default filtering (r_textureMode GL_LINEAR_MIPMAP_NEAREST):
    // bilinear within the nearest mipmap level.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, mipmaps ? GL_LINEAR_MIPMAP_NEAREST : GL_LINEAR);
    // GL 1.4's automatic mipmaps: the level's pictures are minified far away.
    glTexParameteri(GL_TEXTURE_2D, GL_GENERATE_MIPMAP, mipmaps ? GL_TRUE : GL_FALSE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 image.rgba.data());
    glBindTexture(GL_TEXTURE_2D, 0);
    return texture;
}
}  // namespace

SceneRenderer::SceneRenderer(const Scene &scene, const Hierarchy &hierarchy, Look look) : hierarchy_(hierarchy)
{
    auto GenBuffers = reinterpret_cast<PFNGLGENBUFFERSPROC>(gl::get_proc_address("glGenBuffers"));
    auto BufferData = reinterpret_cast<PFNGLBUFFERDATAPROC>(gl::get_proc_address("glBufferData"));
    BindBuffer_ = reinterpret_cast<PFNGLBINDBUFFERPROC>(gl::get_proc_address("glBindBuffer"));
    DeleteBuffers_ = reinterpret_cast<PFNGLDELETEBUFFERSPROC>(gl::get_proc_address("glDeleteBuffers"));
    if (!GenBuffers || !BufferData || !BindBuffer_ || !DeleteBuffers_)
        throw std::runtime_error("SceneRenderer needs vertex buffer objects (GL 1.5)");

    textured_ = look == Look::scene && carries_look(scene);
    stride_ = GLsizei(textured_ ? sizeof(TexturedVertex) : sizeof(Vertex));
    if (textured_) {
        ActiveTexture_ = reinterpret_cast<TextureUnitProc>(gl::get_proc_address("glActiveTexture"));
        ClientActiveTexture_ =
            reinterpret_cast<TextureUnitProc>(gl::get_proc_address("glClientActiveTexture"));
        if (!ActiveTexture_ || !ClientActiveTexture_)
            throw std::runtime_error("SceneRenderer's scene look needs multitexture (GL 1.3)");
        // Only the pictures a mesh uses, each once.
        textures_.assign(scene.images.size(), 0);
        for (const Mesh &m : scene.meshes)
            if (m.image >= 0 && std::size_t(m.image) < scene.images.size() && !textures_[std::size_t(m.image)])
                textures_[std::size_t(m.image)] = upload(scene.images[std::size_t(m.image)], true);
        if (scene.lightmap_atlas >= 0 && std::size_t(scene.lightmap_atlas) < scene.images.size())
            atlas_ = upload(scene.images[std::size_t(scene.lightmap_atlas)], false);
    }

    const auto &nodes = hierarchy.nodes();
    batches_.assign(textured_ ? nodes.size() : 0, {});
    std::vector<TexturedVertex> textured_vertices;
    buffers_.assign(nodes.size(), 0);
    vertex_counts_.assign(nodes.size(), 0);
    see_through_counts_.assign(nodes.size(), 0);
    std::vector<Vertex> vertices;
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
        if (!nodes[n].leaf() || nodes[n].triangle_count == 0)
            continue;
        if (textured_) {
            // The leaf's occluders, then its see-through triangles (the
            // hierarchy's order), each part sorted into batches of one
            // texture and lightmapping.
            std::vector<std::uint32_t> order(nodes[n].triangle_count);
            for (std::uint32_t t = 0; t < order.size(); ++t)
                order[t] = t;
            const std::uint32_t occluders = nodes[n].occluder_triangles;
            auto key = [&](std::uint32_t t) {
                return batch_key(scene.meshes[hierarchy.triangles()[nodes[n].first_triangle + t].mesh]);
            };
            auto by_key = [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); };
            std::stable_sort(order.begin(), order.begin() + occluders, by_key);
            std::stable_sort(order.begin() + occluders, order.end(), by_key);
            textured_vertices.clear();
            std::vector<Batch> &batches = batches_[n];
            for (std::uint32_t k = 0; k < order.size(); ++k) {
                const TriangleRef &ref = hierarchy.triangles()[nodes[n].first_triangle + order[k]];
                const Mesh &mesh = scene.meshes[ref.mesh];
                const GLuint texture =
                    mesh.image >= 0 && std::size_t(mesh.image) < textures_.size() ? textures_[std::size_t(mesh.image)] : 0;
                const bool lightmapped = mesh.lightmapped && atlas_ && mesh.lightmap_coords.size() == mesh.positions.size();
                // A new batch where the key changes or the see-through part begins.
                if (batches.empty() || batches.back().texture != texture || batches.back().lightmapped != lightmapped ||
                    k == occluders)
                    batches.push_back({GLint(textured_vertices.size()), 0, texture, lightmapped});
                for (int c = 0; c < 3; ++c) {
                    const std::uint32_t i = mesh.indices[ref.first_index + c];
                    TexturedVertex v{{mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z}, {}, {0, 0}, {0, 0}};
                    look_colour(mesh, i, v.color);
                    if (!mesh.occluder)
                        v.color[3] = see_through_alpha;
                    if (i < mesh.texcoords.size())
                        v.st[0] = mesh.texcoords[i].x, v.st[1] = mesh.texcoords[i].y;
                    if (lightmapped)
                        v.lightmap[0] = mesh.lightmap_coords[i].x, v.lightmap[1] = mesh.lightmap_coords[i].y;
                    textured_vertices.push_back(v);
                }
                batches.back().count += 3;
            }
            GenBuffers(1, &buffers_[n]);
            BindBuffer_(GL_ARRAY_BUFFER, buffers_[n]);
            BufferData(GL_ARRAY_BUFFER, GLsizeiptr(textured_vertices.size() * sizeof(TexturedVertex)),
                       textured_vertices.data(), GL_STATIC_DRAW);
            vertex_counts_[n] = GLsizei(textured_vertices.size());
            see_through_counts_[n] = GLsizei(3 * (nodes[n].triangle_count - occluders));
            any_see_through_ = any_see_through_ || see_through_counts_[n] > 0;
            continue;
        }
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
    for (GLuint t : textures_)
        if (t)
            glDeleteTextures(1, &t);
    if (atlas_)
        glDeleteTextures(1, &atlas_);
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

std::uint32_t SceneRenderer::draw_batches(std::uint32_t node, GLint first, GLsizei count) const
{
    BindBuffer_(GL_ARRAY_BUFFER, buffers_[node]);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(3, GL_FLOAT, stride_, reinterpret_cast<const void *>(offsetof(TexturedVertex, position)));
    glColorPointer(4, GL_UNSIGNED_BYTE, stride_, reinterpret_cast<const void *>(offsetof(TexturedVertex, color)));
    // Unit 0: the texture times the vertex colour; unit 1: times the lightmap.
    for (GLenum unit : {GL_TEXTURE0, GL_TEXTURE1}) {
        ClientActiveTexture_(unit);
        glEnableClientState(GL_TEXTURE_COORD_ARRAY);
        glTexCoordPointer(2, GL_FLOAT, stride_,
                          reinterpret_cast<const void *>(unit == GL_TEXTURE0 ? offsetof(TexturedVertex, st)
                                                                              : offsetof(TexturedVertex, lightmap)));
    }
    GLuint bound = 0;
    bool lightmap_on = false, texture_on = false;
    ActiveTexture_(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, atlas_);
    for (const Batch &b : batches_[node]) {
        const GLint lo = std::max(first, b.first), hi = std::min(first + count, b.first + b.count);
        if (lo >= hi)
            continue;
        if (b.lightmapped != lightmap_on) {
            ActiveTexture_(GL_TEXTURE1);
            b.lightmapped ? glEnable(GL_TEXTURE_2D) : glDisable(GL_TEXTURE_2D);
            lightmap_on = b.lightmapped;
        }
        if ((b.texture != 0) != texture_on || (b.texture && b.texture != bound)) {
            ActiveTexture_(GL_TEXTURE0);
            if (b.texture) {
                glEnable(GL_TEXTURE_2D);
                glBindTexture(GL_TEXTURE_2D, b.texture);
                bound = b.texture;
            } else {
                glDisable(GL_TEXTURE_2D);
            }
            texture_on = b.texture != 0;
        }
        glDrawArrays(GL_TRIANGLES, lo, hi - lo);
    }
    ActiveTexture_(GL_TEXTURE1);
    glDisable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, 0);
    ClientActiveTexture_(GL_TEXTURE1);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    ActiveTexture_(GL_TEXTURE0);
    glDisable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, 0);
    ClientActiveTexture_(GL_TEXTURE0);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glDisableClientState(GL_COLOR_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
    BindBuffer_(GL_ARRAY_BUFFER, 0);
    return std::uint32_t(count / 3);
}

std::uint32_t SceneRenderer::draw_leaf(std::uint32_t node, LeafPart part) const
{
    const auto [first, count] = part_range(part, vertex_counts_[node], see_through_counts_[node]);
    if (!buffers_[node] || count == 0)
        return 0;
    if (textured_)
        return draw_batches(node, first, count);
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
    glVertexPointer(3, GL_FLOAT, stride_, reinterpret_cast<const void *>(offsetof(Vertex, position)));
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
