// SPDX-License-Identifier: MIT
// Draws the leaves of a hierarchy with OpenGL (compatibility profile), one
// vertex buffer per leaf, colours pre-lit on the CPU once (render/shading.h)
// so that frames need no lighting state. Also draws node boxes as occlusion proxies.
//
// See-through meshes (Mesh::occluder false: glass, water, fog) hide nothing,
// so a frame draws them last, as a real-time renderer draws translucent
// surfaces after the opaque ones (Quake III's shaders sort blended surfaces
// after opaque ones; Akenine-Moller, Haines and Hoffman, "Real-Time
// Rendering", 4th ed., section 5.5, "Transparency, Alpha, and
// Compositing"): every leaf's occluders first (draw_leaf), in
// whatever order the culling strategy chooses, then the see-through
// triangles of the leaves it drew (draw_see_through), blended over them,
// depth tested but never writing depth. So the depth buffer the occlusion
// unit's tests read while the frame is drawn (and last frame's depth, the
// ID buffer of the oracle) holds occluders only: a see-through mesh never
// hides a box behind it, whatever strategy tests the box and whatever the
// drawing order. The frame stays independent of the order leaves are drawn
// in (the see-through pass sorts them itself), which is what lets a culled
// frame be compared pixel by pixel with the unculled one
// (evaluation/lost_pixels.h).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl_headers.h"
#include "spatial/hierarchy.h"

namespace occu {

// How a frame looks. flat: every mesh in its one colour, pre-lit
// (render/shading.h): what the procedural city calls for. scene: what the
// scene itself carries (Mesh::texcoords, image, lightmapped, vertex_light:
// a Quake III level read with its look, scene/quake3_bsp.h): each mesh's
// texture modulated by its lightmap, or by its vertex light where it has
// none; a mesh without such data is drawn flat. Only the colour pass
// (draw_leaf, draw_see_through) uses the look; the passes that write no
// colour (draw_leaf_flat: occluders' depth, ID buffers) never texture.
enum class Look { flat, scene };

// Which of a leaf's triangles to draw: those of occluder meshes, those of
// see-through meshes (Mesh::occluder), or both.
enum class LeafPart { occluders, see_through, all };

class SceneRenderer {
public:
    // Needs a current context.
    SceneRenderer(const Scene &scene, const Hierarchy &hierarchy, Look look = Look::flat);
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer &) = delete;
    SceneRenderer &operator=(const SceneRenderer &) = delete;

    // Draws the triangles of leaf `node` (by default its occluders: a
    // frame's first pass, above), with the caller's GL state; returns how many.
    std::uint32_t draw_leaf(std::uint32_t node, LeafPart part = LeafPart::occluders) const;
    // Draws leaf `node` in one flat colour (for ID buffers and occluder
    // depth; the caller sets it with glColor and turns dithering off). By
    // default its occluders only: what hides what lies behind it.
    void draw_leaf_flat(std::uint32_t node, LeafPart part = LeafPart::occluders) const;
    // True when leaf `node` holds triangles of see-through meshes.
    bool has_see_through(std::uint32_t node) const { return see_through_counts_[node] > 0; }
    // A frame's last pass (above): the see-through triangles of `leaves`
    // (those without any are skipped), the leaf whose box centre is
    // farthest from `eye` first (ties by node), blended half over what is
    // drawn, depth tested with the caller's test, depth not written.
    // Returns how many triangles it drew; without see-through meshes in the
    // scene it does nothing.
    std::uint32_t draw_see_through(const std::vector<std::uint32_t> &leaves, const glm::vec3 &eye) const;
    // The opacity of see-through triangles in frames (their vertex alpha):
    // a level's own shaders are not read, so one factor stands for all.
    static constexpr std::uint8_t see_through_alpha = 128;
    // Draws the faces of `box` (an occlusion proxy: no colour needed).
    static void draw_box(const Aabb &box);

    // Whether frames are textured (Look::scene on a scene that carries a look).
    bool textured() const { return textured_; }

private:
    // A run of a leaf's vertices drawn with one texture and lightmapping:
    // [first, first + count) of its buffer.
    struct Batch {
        GLint first;
        GLsizei count;
        GLuint texture;   // 0: none
        bool lightmapped;
    };
    std::uint32_t draw_batches(std::uint32_t node, GLint first, GLsizei count) const;

    const Hierarchy &hierarchy_;
    bool textured_ = false;
    GLsizei stride_ = 0;
    std::vector<GLuint> textures_;              // per Scene::images (0: not used by any mesh)
    GLuint atlas_ = 0;                          // the lightmap atlas
    std::vector<std::vector<Batch>> batches_;   // per node, when textured
    // glActiveTexture and glClientActiveTexture (GL 1.3).
    using TextureUnitProc = void(APIENTRY *)(GLenum);
    TextureUnitProc ActiveTexture_ = nullptr, ClientActiveTexture_ = nullptr;
    std::vector<GLuint> buffers_;          // per node; 0 for inner nodes
    std::vector<GLsizei> vertex_counts_;       // per node: its occluders' vertices, then the see-through ones
    std::vector<GLsizei> see_through_counts_;  // per node: the see-through vertices
    bool any_see_through_ = false;
    PFNGLBINDBUFFERPROC BindBuffer_ = nullptr;
    PFNGLDELETEBUFFERSPROC DeleteBuffers_ = nullptr;
};

}  // namespace occu
