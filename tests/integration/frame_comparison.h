// SPDX-License-Identifier: MIT
// What the integration tests of conservative culling share: one frame
// drawn through a culler into the current context, read back, and how two
// such frames differ.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "culling/culler.h"
#include "gl/gl_headers.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"
#include "traversal/traversal.h"

namespace occu::integration {

struct DrawnFrame {
    std::vector<std::uint8_t> pixels;   // RGBA8, bottom row first
    std::uint64_t triangles = 0;
    std::vector<std::uint32_t> leaves;  // drawn, in drawing order
};

// Clears colour and depth, loads the frame's camera and draws the hierarchy
// through `culler` front to back (traversal/traversal.h).
inline DrawnFrame draw_frame(const gl::OffscreenContext &ctx, const SceneRenderer &renderer, const Hierarchy &h,
                             Culler &culler, const Frame &frame, const TraversalOptions &options)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl::load_camera(frame.camera);
    FrameStats s = render_hierarchy(renderer, h, culler, frame, options);
    glFinish();
    const std::size_t n = std::size_t(ctx.width()) * std::size_t(ctx.height()) * 4;
    return {std::vector<std::uint8_t>(ctx.pixels(), ctx.pixels() + n), s.triangles, std::move(s.drawn)};
}

// The unculled frame in the order a strategy that orders the frame itself
// (Culler::orders_frame, e.g. chc) drew: its leaves `first` in its order,
// then every other leaf. Where faces tie in depth the leaf drawn first
// keeps the pixel (GL_LESS), and such a strategy draws in an order of its
// own (results handled as they come), so the common traversal's unculled
// frame differs from it in tied pixels however well it culls. In this
// reference a leaf it culled changes a pixel only where it is strictly in
// front of what it drew there: where it was visible.
inline DrawnFrame draw_unculled_after(const gl::OffscreenContext &ctx, const SceneRenderer &renderer, const Hierarchy &h,
                                      const Frame &frame, const std::vector<std::uint32_t> &first)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl::load_camera(frame.camera);
    DrawnFrame d;
    std::vector<std::uint8_t> done(h.nodes().size(), 0);
    for (std::uint32_t leaf : first) {
        d.triangles += renderer.draw_leaf(leaf);
        done[leaf] = 1;
        d.leaves.push_back(leaf);
    }
    for (std::uint32_t n = 0; n < h.nodes().size(); ++n)
        if (h.nodes()[n].leaf() && !done[n]) {
            d.triangles += renderer.draw_leaf(n);
            d.leaves.push_back(n);
        }
    d.triangles += renderer.draw_see_through(d.leaves, frame.camera.position);
    glFinish();
    const std::size_t bytes = std::size_t(ctx.width()) * std::size_t(ctx.height()) * 4;
    d.pixels.assign(ctx.pixels(), ctx.pixels() + bytes);
    return d;
}

// Pixels (4 bytes each) in which frames of the same size differ.
inline std::size_t differing_pixels(const std::vector<std::uint8_t> &a, const std::vector<std::uint8_t> &b)
{
    std::size_t n = 0;
    for (std::size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4)
        n += a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2] || a[i + 3] != b[i + 3];
    return n;
}

}  // namespace occu::integration
