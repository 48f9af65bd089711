// Occluder selection at run time (Poon and Wang, section 6.1): which
// hierarchy leaves the opacity-map cullers render as occluders.
//   projected size (PS)  the leaves in the frustum whose boxes subtend the
//                        largest solid angle;
//   first hit (FH)       the leaves covering the most pixels of the frame's
//                        ID buffer (what the eye sees first);
//   minimum occluder set (MOS) comes from preprocessing: occluder_database.h.
// The paper picks primitives; occu picks leaves (up to 256 triangles), the
// unit its hierarchy draws.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"

namespace occu {

std::vector<std::uint32_t> occluders_by_projected_size(const Hierarchy &hierarchy, const Camera &camera,
                                                       const Frustum &frustum, std::size_t limit);

// Renders an ID buffer of width x height into the current framebuffer.
std::vector<std::uint32_t> occluders_by_first_hit(const SceneRenderer &renderer, const Hierarchy &hierarchy,
                                                  const Camera &camera, const Frustum &frustum, int width,
                                                  int height, std::size_t limit);

// Pixels each leaf covers in an ID buffer (index: node; from render_leaf_ids).
std::vector<std::uint32_t> pixels_per_leaf(const std::vector<std::uint32_t> &ids, std::size_t nodes);

}  // namespace occu
