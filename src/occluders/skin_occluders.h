// SPDX-License-Identifier: MIT
// Occluder skins at run time (Leone et al., section 5): the skins of the
// scene's meshes (occluder_skins.h), frustum-culled each
// frame, the largest on screen first, and their faces that face the eye
// rasterized as quads into a CPU depth buffer (raster/depth_rasterizer.h).
// Shared by the strategies that take their occluders from skins
// (occluders/sources.h: skin_occluder_source).
// The scene's own triangles join them in occluders/triangle_occluders.h,
// both in occluders/depth_occluders.h.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "culling/culler.h"
#include "culling/settings.h"
#include "occluders/brush_occluders.h"
#include "occluders/occluder_skins.h"
#include "raster/depth_rasterizer.h"
#include "scene/scene.h"

namespace occu {

class SkinOccluders {
public:
    // From the skin database at `database` (refused, naming why, when made
    // for another scene), or with an empty path made from `scene` now with
    // `options` (once per scene and options in a process). Each mesh keeps
    // its first `boxes_per_mesh` boxes (the largest first).
    SkinOccluders(const Scene &scene, const std::string &database, int boxes_per_mesh,
                  const SkinOptions &options = {});
    // As its strategy's settings ask (occluders/sources.h: the skin
    // source's settings).
    SkinOccluders(const Scene &scene, const Settings &settings);

    // Renders the usable skins in `frame`'s frustum into `raster` (begun
    // for the frame): at most `limit` of them (0: all), chosen by the solid angle
    // their boxes subtend, drawn nearest first, skipping those the ones
    // before already hide. Returns how many it drew.
    std::size_t render(const Frame &frame, DepthRasterizer &raster, std::size_t limit);

    // Whether skin `i` may stand for its mesh in `frame`: only where the
    // mesh's bounding box lies wholly beyond the near plane. A skin hides
    // what lies behind it because the mesh's surface in front of it is
    // drawn; a near plane through the mesh clips that surface away, and an
    // eye inside the mesh sees its walls from behind, where back-face
    // culling drops them: in both GL shows what the skin would hide.
    // With skin-source=brushes (a Quake III level's box brushes,
    // occluders/brush_occluders.h, LevelBrushOccluders::BoxBrush) also only where every
    // side of the box whose outer half-space holds the eye is drawn all
    // over (a ray enters the box through such a side and must meet a drawn
    // face there), and no solid brush comes nearer the eye than the near
    // rectangle's corners, nor holds it (the near plane must not clip that
    // face away).
    bool usable(std::size_t i, const Frame &frame) const;

    std::size_t size() const { return boxes_.size(); }
    // The share of the scene's occluder triangles in meshes that have no
    // skin here: 1 without skins, 0 with a level's box brushes (they stand
    // for the level's meshes).
    double share_without_skins() const;
    const std::vector<Aabb> &boxes() const { return boxes_; }
    // The bounding box of skin i's mesh.
    const Aabb &mesh_bounds(std::size_t i) const { return mesh_bounds_[i]; }

private:
    std::vector<Aabb> boxes_;
    std::vector<Aabb> mesh_bounds_;   // per skin, its mesh's
    // The scene's occluder triangles, and those in meshes with a skin kept.
    std::size_t occluder_triangles_ = 0, skinned_triangles_ = 0;
    std::vector<std::pair<float, std::uint32_t>> chosen_;

    // skin-source=brushes: every solid brush's bounds, and whether the eye
    // of the frame last asked about is clear of them.
    bool brushes_ = false;
    LevelBrushOccluders brush_occluders_;
    std::vector<Aabb> solids_;
    bool eye_clear(const Frame &frame) const;
    mutable glm::mat4 clear_view_projection_{0.0f};
    mutable bool clear_ = false;

    // The scene, whose level (scene/level.h) eye_clear reads.
    const Scene *scene_ = nullptr;
};

}  // namespace occu
