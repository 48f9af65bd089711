// SPDX-License-Identifier: MIT
// The scene's own triangles as occluders in a CPU depth buffer
// (raster/depth_rasterizer.h), for meshes with no volume for skins (thin
// walls, open meshes; occluders/skin_occluders.h): those of occluder
// meshes only, chosen per frame by projected area, the largest first up
// to a budget (occluder-triangles), and rasterized by the same
// conservative rasterizer as skins, as Intel's Masked Occlusion Culling
// takes a game's own meshes. A front-facing triangle in the frustum is
// drawn by GL wherever nothing nearer hides it, and what hides it hides
// what lies behind it, so its farthest depth over a fully covered depth
// pixel is a safe occluder (Leone, section 3: occluders fuse in the
// buffer). A triangle across the near plane is clipped there by the
// rasterizer (the part GL draws), never dropped nor taken whole.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "culling/culler.h"
#include "culling/settings.h"
#include "raster/depth_rasterizer.h"
#include "scene/scene.h"

namespace occu {

class TriangleOccluders {
public:
    // As the settings ask (occluders/sources.h, triangle_occluder_source):
    // occluder-triangles, the budget (0, or a family without the setting:
    // none), at least `least_budget`, and with coverage=merged the
    // triangle across each edge. Keeps `scene` by reference.
    TriangleOccluders(const Scene &scene, const Settings &settings, std::size_t least_budget = 0);

    // Renders into `raster` at most budget() of the scene's occluder
    // triangles that face the eye in `frame`'s frustum, the largest
    // projected area first, drawn nearest first. Returns how many it drew.
    std::size_t render(const Frame &frame, DepthRasterizer &raster);
    std::size_t budget() const { return budget_; }

private:
    const Scene *scene_;
    std::size_t budget_ = 0;
    // Mesh and first index of each, from occluder meshes only.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> triangles_;
    std::vector<glm::vec3> across_;   // coverage=merged: 3 per triangle (shared_edge_opposites)
    std::vector<std::pair<float, std::uint32_t>> chosen_triangles_;
};

}  // namespace occu
