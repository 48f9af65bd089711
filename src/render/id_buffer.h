// SPDX-License-Identifier: MIT
// ID rendering: each leaf drawn in a flat colour that encodes its index,
// depth tested, then read back, so that every pixel names the leaf seen
// there. The oracle (exact visibility), first-hit occluder selection and
// the minimum-occluder-set preprocessing's redundancy removal (Poon and
// Wang, section 4.3) all read scenes this way. It draws into a framebuffer
// object of its own, never the caller's.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "camera/camera.h"
#include "gl/framebuffer.h"
#include "render/scene_renderer.h"

namespace occu {

class IdBuffer {
public:
    // Where the IDs are drawn: a framebuffer object of the ID buffer's own
    // (the caller's framebuffer is untouched), or the framebuffer bound
    // when render() is called (its colour and depth are overwritten): the
    // one frames are drawn into, whose rasterization an exact answer must
    // share (softpipe rasterizes a window-system framebuffer upside down
    // from unsnapped vertices, so an edge pixel can fall otherwise in a
    // framebuffer object).
    enum class Target { own_framebuffer, bound_framebuffer };

    // Needs a current context; draws with `renderer`.
    explicit IdBuffer(const SceneRenderer &renderer, Target target = Target::own_framebuffer)
        : renderer_(renderer), target_kind_(target)
    {
    }

    // Draws `leaves` as seen by `camera` into width x height pixels and
    // returns, per pixel (rows bottom-up), the leaf index + 1 seen there, 0
    // for background. Indices must be below 2^24 - 1. Only occluders are
    // drawn (Mesh::occluder): a see-through surface hides nothing, so a
    // pixel names the first occluder along its ray, what occluder selection
    // wants. `see_through_shown`, when given, receives the leaves of
    // `leaves` whose see-through triangles show in front of those
    // occluders somewhere (one occlusion query each, with the frame's depth
    // test): what a frame draws over the occluders (render/scene_renderer.h).
    std::vector<std::uint32_t> render(const Camera &camera, const std::vector<std::uint32_t> &leaves, int width,
                                      int height, std::vector<std::uint32_t> *see_through_shown = nullptr);

private:
    const SceneRenderer &renderer_;
    Target target_kind_;
    std::optional<gl::Framebuffer> target_;
};

// Pixels each leaf covers in an ID buffer (index: node).
std::vector<std::uint32_t> pixels_per_leaf(const std::vector<std::uint32_t> &ids, std::size_t nodes);

}  // namespace occu
