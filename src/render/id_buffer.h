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
    // Needs a current context; draws with `renderer`.
    explicit IdBuffer(const SceneRenderer &renderer) : renderer_(renderer) {}

    // Draws `leaves` as seen by `camera` into width x height pixels and
    // returns, per pixel (rows bottom-up), the leaf index + 1 seen there, 0
    // for background. Indices must be below 2^24 - 1.
    std::vector<std::uint32_t> render(const Camera &camera, const std::vector<std::uint32_t> &leaves, int width,
                                      int height);

private:
    const SceneRenderer &renderer_;
    std::optional<gl::Framebuffer> target_;
};

// Pixels each leaf covers in an ID buffer (index: node).
std::vector<std::uint32_t> pixels_per_leaf(const std::vector<std::uint32_t> &ids, std::size_t nodes);

}  // namespace occu
