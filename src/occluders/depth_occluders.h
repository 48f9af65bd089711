// SPDX-License-Identifier: MIT
// The occluders of the strategies that rasterize occluders into a CPU
// depth buffer (raster/depth_rasterizer.h) each frame: the skins
// (occluders/skin_occluders.h), then the scene's own triangles up to their
// budget (occluders/triangle_occluders.h), as the settings of the two
// sources ask (occluders/sources.h: skin_occluder_source and
// triangle_occluder_source).
#pragma once

#include <cstddef>

#include "culling/culler.h"
#include "culling/settings.h"
#include "occluders/skin_occluders.h"
#include "occluders/sources.h"
#include "occluders/triangle_occluders.h"
#include "raster/depth_rasterizer.h"
#include "scene/scene.h"

namespace occu {

class DepthOccluders {
public:
    // Keeps `scene` and `hierarchy` by reference; the triangles are chosen
    // leaf by leaf of `hierarchy` where given (TriangleOccluders). Where
    // meshes without skins hold at least scene_triangle_share of the
    // scene's occluder triangles and the settings ask for scene-triangles,
    // the triangle budget is at least scene_triangle_budget
    // (occluders/sources.h).
    DepthOccluders(const Scene &scene, const Settings &settings, const Hierarchy *hierarchy = nullptr)
        : skins_(scene, settings),
          triangles_(scene, settings,
                     skins_.share_without_skins() >= scene_triangle_share && settings.knows("scene-triangles") &&
                             settings.on("scene-triangles")
                         ? std::size_t(scene_triangle_budget)
                         : 0,
                     hierarchy)
    {
    }

    // Renders into `raster` (begun for the frame) at most `skin_limit`
    // skins (0: all), then the triangle budget. Returns how many of both
    // it drew.
    std::size_t render(const Frame &frame, DepthRasterizer &raster, std::size_t skin_limit)
    {
        return skins_.render(frame, raster, skin_limit) + triangles_.render(frame, raster);
    }

    const SkinOccluders &skins() const { return skins_; }

private:
    SkinOccluders skins_;
    TriangleOccluders triangles_;
};

}  // namespace occu
