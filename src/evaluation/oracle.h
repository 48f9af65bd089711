// SPDX-License-Identifier: MIT
// The exact-visibility oracle: which leaves of the hierarchy contribute at
// least one pixel to a frame, from an ID buffer (every leaf in the frustum
// drawn in its own flat colour, then read back). It draws into the bound
// framebuffer, the one the frames are drawn into, so that its pixels are
// the frame's (render/id_buffer.h says why), and overwrites its colour and
// depth: callers draw their frames after it. A see-through mesh
// (Mesh::occluder false) hides nothing: the ID buffer holds occluders only,
// so what lies behind glass is seen, and a leaf whose see-through triangles
// pass the depth test of those occluders is seen too, as the frame blends
// them over the occluders (render/scene_renderer.h). Culling efficiency is measured against it, as Poon and Wang
// (section 6) compare with the exact visible set, and the `ideal` reference
// strategy draws exactly its visible leaves.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.h"
#include "render/id_buffer.h"
#include "spatial/hierarchy.h"

namespace occu {

struct VisibilityTruth {
    std::vector<std::uint32_t> in_frustum;   // leaves not outside the view frustum, sorted
    std::vector<std::uint32_t> visible;      // leaves with at least one pixel, sorted
};

class Oracle {
public:
    Oracle(const SceneRenderer &renderer, const Hierarchy &hierarchy)
        : hierarchy_(hierarchy), ids_(renderer, IdBuffer::Target::bound_framebuffer)
    {
    }
    VisibilityTruth see(const Camera &camera, int width, int height);

private:
    const Hierarchy &hierarchy_;
    IdBuffer ids_;
};

// How a strategy did against the truth, for one frame. Efficiency:
// occluded leaves culled / occluded leaves, where "occluded" means in the
// frustum but invisible.
struct CullingQuality {
    std::uint32_t occluded = 0;           // leaves in the frustum the oracle does not see
    std::uint32_t occluded_culled = 0;    // ... that the strategy did not draw
    std::uint32_t visible_culled = 0;     // visible leaves the strategy did not draw (0 if conservative)
    double efficiency() const { return occluded ? double(occluded_culled) / occluded : 1.0; }
};

CullingQuality compare_with_truth(const VisibilityTruth &truth, std::vector<std::uint32_t> drawn);

}  // namespace occu
