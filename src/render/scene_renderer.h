// Draws the leaves of a hierarchy with OpenGL (compatibility profile), one
// vertex buffer per leaf, colours pre-lit on the CPU once (render/shading.h)
// so that frames need no lighting state. Also draws node boxes as occlusion proxies.
#pragma once

#include <cstdint>
#include <vector>

#include "gl/gl_headers.h"
#include "spatial/hierarchy.h"

namespace occu {

class SceneRenderer {
public:
    // Needs a current context.
    SceneRenderer(const Scene &scene, const Hierarchy &hierarchy);
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer &) = delete;
    SceneRenderer &operator=(const SceneRenderer &) = delete;

    // Draws the triangles of leaf `node`; returns how many.
    std::uint32_t draw_leaf(std::uint32_t node) const;
    // Draws leaf `node` in one flat colour (for ID buffers; the caller sets
    // it with glColor and turns dithering off).
    void draw_leaf_flat(std::uint32_t node) const;
    // Draws the faces of `box` (an occlusion proxy: no colour needed).
    static void draw_box(const Aabb &box);

private:
    const Hierarchy &hierarchy_;
    std::vector<GLuint> buffers_;          // per node; 0 for inner nodes
    std::vector<GLsizei> vertex_counts_;
    PFNGLBINDBUFFERPROC BindBuffer_ = nullptr;
    PFNGLDELETEBUFFERSPROC DeleteBuffers_ = nullptr;
};

}  // namespace occu
