// SPDX-License-Identifier: MIT
// Occluder selection at run time (Poon and Wang, section 6.1): which
// hierarchy leaves an occlusion strategy renders as occluders.
//   projected size (PS)  the leaves in the frustum whose boxes subtend the
//                        largest solid angle;
//   first hit (FH)       the leaves covering the most pixels of the frame's
//                        ID buffer (what the eye sees first);
//   minimum occluder set (MOS) comes from preprocessing
//                        (occluder_database.h).
// The paper picks primitives; occu picks leaves, the unit its hierarchy draws.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.h"
#include "render/id_buffer.h"
#include "spatial/hierarchy.h"

namespace occu {

std::vector<std::uint32_t> occluders_by_projected_size(const Hierarchy &hierarchy, const Camera &camera,
                                                       const Frustum &frustum, std::size_t limit);

// A budget in triangles rather than leaves: the first leaves of
// `best_first` (the best first) while the triangles taken so far are fewer
// than `budget`, counted by `triangles` (indexed by node); the leaf that
// reaches the budget is taken, and at least one leaf when there is one.
// So the share of the scene drawn as occluders stays the same when the
// hierarchy's leaves are made smaller or larger.
std::vector<std::uint32_t> first_leaves_within_triangles(const std::vector<std::uint32_t> &best_first,
                                                         const std::vector<std::uint32_t> &triangles,
                                                         std::size_t budget);

// Renders an ID buffer of width x height with `ids`.
std::vector<std::uint32_t> occluders_by_first_hit(IdBuffer &ids, const Hierarchy &hierarchy, const Camera &camera,
                                                  const Frustum &frustum, int width, int height, std::size_t limit);

}  // namespace occu
