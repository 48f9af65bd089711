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
//
// Choosing does not look at every triangle every frame: the triangles are
// grouped by the hierarchy's leaves, each group ranked by world area, and
// a frame visits the leaves in the frustum in order of the largest
// projected area any of their triangles may have (its largest world area
// over the leaf's nearest view depth squared); it stops at the first
// leaf, and within a leaf at the first triangle, that cannot beat the
// budget's smallest score so far. Which triangles are chosen decides only
// how much is culled, never whether it is safe: every one drawn is a
// triangle GL draws.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "culling/culler.h"
#include "culling/settings.h"
#include "raster/depth_rasterizer.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"

namespace occu {

class TriangleOccluders {
public:
    // As the settings ask (occluders/sources.h, triangle_occluder_source):
    // occluder-triangles, the budget (0, or a family without the setting:
    // none), at least `least_budget`, and with coverage=merged the
    // triangle across each edge. Grouped by `hierarchy`'s leaves where
    // given (null: one group of all). Keeps `scene` and `hierarchy` by
    // reference.
    TriangleOccluders(const Scene &scene, const Settings &settings, std::size_t least_budget = 0,
                      const Hierarchy *hierarchy = nullptr);

    // Renders into `raster` at most budget() of the scene's occluder
    // triangles that face the eye in `frame`'s frustum, the largest
    // projected area first, drawn nearest first. Returns how many it drew.
    std::size_t render(const Frame &frame, DepthRasterizer &raster);
    // What render() draws for `frame`: three indices into corners() a
    // triangle, nearest first. Valid until the next call.
    const std::vector<std::uint32_t> &choose(const Frame &frame);
    // The occluder triangles' corners, three a triangle.
    const std::vector<glm::vec3> &corners() const { return corners_; }
    std::size_t budget() const { return budget_; }

private:
    struct Group {
        Aabb bounds;
        std::uint32_t first = 0, count = 0;   // in corners_ / 3, the largest world area first
        float largest = 0.0f;                 // twice the world area of its first triangle
    };
    // The score of triangle t (twice its projected area, see render), or
    // nothing (back-facing, outside the frustum).
    bool score(std::uint32_t t, const glm::mat4 &vp, const Frame &frame, float &out) const;

    const Hierarchy *hierarchy_ = nullptr;
    std::size_t budget_ = 0;
    std::vector<glm::vec3> corners_;   // 3 per triangle, grouped
    std::vector<float> twice_area_;    // per triangle, world
    std::vector<Group> groups_;
    std::vector<std::uint32_t> leaf_group_;   // per hierarchy node: its group, or none (~0)
    std::vector<glm::vec3> across_;   // coverage=merged: 3 per triangle (shared_edge_opposites)
    // Per frame: (score, triangle) of the best so far, a min-heap; then
    // (nearest w, triangle); their corners' indices and the triangles
    // across them.
    std::vector<std::pair<float, std::uint32_t>> chosen_;
    std::vector<std::pair<float, std::uint32_t>> groups_by_bound_;
    std::vector<std::uint32_t> drawn_indices_;
    std::vector<glm::vec3> drawn_across_;
};

}  // namespace occu
