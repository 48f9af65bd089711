// SPDX-License-Identifier: MIT
// The per-frame occluder sources several strategy families draw from,
// each declared once here, with the settings and databases it reads
// (culling/registry.h, OccluderSource). A family names the sources it
// takes occluders from in its StrategyFamily::occluder_sources; the
// registry adds their settings and databases to the family's own. They
// belong to no one paper: the families of several papers share them.
//
//   skin_occluder_source      occluder skins (occluders/skin_occluders.h):
//                             boxes inside each closed mesh (Leone et al.,
//                             section 4: occluders/occluder_skins.h), or a
//                             level's box brushes (skin-source=brushes:
//                             occluders/brush_occluders.h); skin-source,
//                             skin-boxes, skin-voxel, skin-database
//   triangle_occluder_source  the scene's own largest triangles, added per
//                             frame to a depth buffer beside the skins, and
//                             the coverage rule of that buffer, which is
//                             what lets the triangles of a mesh fuse along
//                             their shared edges; occluder-triangles,
//                             coverage
//   shadow_occluder_source    a few large occluders per frame from the skins,
//                             for culling in object space
//                             (occluders/shadow_occluders.h); occluders,
//                             aggregate (with the skin source for the skins)
#pragma once

#include <vector>

#include "culling/registry.h"
#include "culling/settings.h"
#include "occluders/occluder_skins.h"

namespace occu {

const OccluderSource &skin_occluder_source();
const OccluderSource &triangle_occluder_source();
const OccluderSource &shadow_occluder_source();

// The skin source's settings and its database: skin-source, skin-boxes,
// skin-voxel and skin-database, the database made with the settings'
// skin-voxel for the scene's meshes (culling/databases.h makes it).
std::vector<SettingSpec> skin_settings();
DatabaseNeed skin_database_need();
// The skins' construction options the settings ask for (skin-voxel).
SkinOptions skin_options(const Settings &settings);

// The triangle source's settings. occluder-triangles: the scene's own
// largest triangles added per frame (0: skins alone). coverage: `whole`,
// a polygon writes only the depth pixels it covers wholly (occluders fuse
// in the buffer, Leone section 3); `merged`, partial coverage of a depth
// pixel's samples also fuses across polygons, as in Masked Occlusion
// Culling (raster/depth_rasterizer.h), so that a mesh's triangles leave no
// seam of empty pixels along their shared edges.
// The CPU depth buffer's resolution (skins, hzb): map-size, its pixels
// along the frame's larger side whatever the frame's size, as Masked
// Occlusion Culling's buffer has a resolution of its own, so that its
// cost does not grow with the frame; the divisor (frame pixels per depth
// pixel, each way) is the larger side over it, rounded up, at most 8 with
// merged coverage. map-divisor, where above 0 (its default is 0), fixes
// the divisor instead: 1 is the frame's own resolution, exact.
SettingSpec map_size_setting(long default_size, std::string what);
SettingSpec map_divisor_setting(std::string what);
int map_divisor(const Settings &settings, int frame_width, int frame_height);

SettingSpec occluder_triangles_setting();
SettingSpec coverage_setting();
// scene-triangles (on): where meshes without skins hold at least
// scene_triangle_share of the scene's occluder triangles (no closed mesh:
// a game level, open models; a building of thin walls whose few closed
// meshes have skins), its own largest triangles join the skins, at least
// scene_triangle_budget of them, so that a family culls with the occluders
// the scene has at its defaults; off: occluder-triangles alone. They are
// chosen among every mesh's, skinned or not (a skin lies inside its mesh,
// so the mesh's own surface hides at least what the skin does). Where the
// skinned meshes hold most triangles the skins stand alone: the city's
// ground, its one mesh without a skin, holds 12 of its 272,796.
SettingSpec scene_triangles_setting();
// adapt-triangles (off): each frame's triangle budget follows what the
// last frame's triangles added to the buffer
// (TriangleOccluders::adapted_budget), up to the budget above.
SettingSpec adapt_triangles_setting();
constexpr long scene_triangle_budget = 1024;
constexpr double scene_triangle_share = 0.5;
// Whether `settings` ask for merged coverage; throws std::invalid_argument
// naming the setting where the rasterizer's divisor is above 8.
bool merges_partial_coverage(const Settings &settings, int divisor);

}  // namespace occu
