// SPDX-License-Identifier: MIT
// The shared occluder sources and their settings: see sources.h.
#include "occluders/sources.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "occluders/triangle_occluders.h"

namespace occu {

SkinOptions skin_options(const Settings &settings)
{
    SkinOptions options;
    options.voxel_size = float(settings.number("skin-voxel"));
    return options;
}

SettingSpec map_size_setting(long default_size, std::string what)
{
    return integer_setting("map-size", default_size, 1, 1 << 14, SettingSpec::Role::cost,
                           what + " along the frame's larger side, whatever the frame's size (the divisor is that "
                                  "side over it, rounded up; map-divisor above 0 fixes the divisor instead)");
}

SettingSpec map_divisor_setting(std::string what)
{
    return integer_setting("map-divisor", 0, 0, 64, SettingSpec::Role::cost,
                           "frame pixels per " + what + ", each way (1: the frame's resolution, exact); 0: from "
                           "map-size");
}

int map_divisor(const Settings &settings, int frame_width, int frame_height)
{
    const long fixed = settings.integer("map-divisor");
    if (fixed > 0)
        return int(fixed);
    const long side = std::max(frame_width, frame_height), size = settings.integer("map-size");
    const int divisor = int(std::max(1L, (side + size - 1) / size));
    // Merged coverage keeps a mask of at most 8 x 8 samples a pixel.
    const bool merged = settings.knows("coverage") && settings.text("coverage") == "merged";
    return merged ? std::min(divisor, 8) : divisor;
}

SettingSpec occluder_triangles_setting()
{
    return integer_setting("occluder-triangles", 0, 0, 1 << 20, SettingSpec::Role::cost,
                           "the scene's own triangles rasterized per frame beside the skins, the largest on screen "
                           "first (for thin walls and open meshes, which have no volume for skins)",
                           "0");
}

SettingSpec coverage_setting()
{
    return choice_setting("coverage", {"whole", "merged"},
                          "depth pixels an occluder polygon covers wholly, or also samples of a pixel that "
                          "several polygons cover together (Masked Occlusion Culling's merge; map divisor 8 or less)",
                          SettingSpec::Role::cost);
}

SettingSpec scene_triangles_setting()
{
    return on_off_setting("scene-triangles", true, SettingSpec::Role::choice,
                          "where meshes without skins hold half the scene's triangles or more (a level, open models, "
                          "thin walls), its own largest triangles join the skins (occluder-triangles " +
                              std::to_string(scene_triangle_budget) + " unless set higher); off: occluder-triangles alone");
}

bool merges_partial_coverage(const Settings &settings, int divisor)
{
    if (!settings.knows("coverage") || settings.text("coverage") != "merged")
        return false;
    if (divisor > 8)
        throw std::invalid_argument("coverage=merged needs a depth buffer of at most 8 x 8 frame pixels a pixel "
                                    "(map-divisor " + std::to_string(divisor) + " given)");
    return true;
}

std::vector<SettingSpec> skin_settings()
{
    return {
        choice_setting("skin-source", {"meshes", "brushes"},
                       "where skins come from: boxes made inside each closed mesh, or a Quake III level's "
                       "box brushes, each from the eyes that see only drawn faces of it (a level's meshes are "
                       "open surfaces and have no skins)"),
        integer_setting("skin-boxes", 8, 1, 1 << 16, SettingSpec::Role::cost, "skin boxes per mesh, the largest first"),
        // Tighter than SkinOptions' default (95% of the city's buildings'
        // bodies against 89%) for seven times its second: what benchmarks
        // made their skin databases with, and made once by the database
        // provider (culling/databases.h).
        number_setting("skin-voxel", 0.25, 0.05, 10.0, SettingSpec::Role::choice,
                       "voxel edge, metres, of the skins made at start or as a skin database (0.5: a seventh of "
                       "the time, looser)"),
        path_setting("skin-database", "the skin database (occu-preprocess skins); without one, skins are made at start"),
    };
}

DatabaseNeed skin_database_need()
{
    DatabaseNeed need;
    need.setting = "skin-database";
    need.name = "skin database";
    need.provenance = [](const DatabaseRequest &r) {
        return OccluderSkinDatabase::provenance_for(r.context.scene, skin_options(r.settings));
    };
    need.make = [](const DatabaseRequest &r, const std::string &path) {
        OccluderSkinDatabase::make(r.context.scene, skin_options(r.settings)).save(path);
    };
    return need;
}

const OccluderSource &skin_occluder_source()
{
    static const OccluderSource source{"occluder skins", skin_settings(), {skin_database_need()}};
    return source;
}

SettingSpec adapt_triangles_setting()
{
    return on_off_setting("adapt-triangles", false, SettingSpec::Role::cost,
                          "each frame's triangle budget is five quarters of the last frame's triangles that "
                          "reached past the buffer (not behind everything there), at most occluder-triangles and at "
                          "least " + std::to_string(TriangleOccluders::adapted_least) +
                              " (or scene-triangles' least, which holds a level at 1024); off: occluder-triangles "
                              "every frame");
}

const OccluderSource &triangle_occluder_source()
{
    static const OccluderSource source{"the scene's own triangles",
                                       {occluder_triangles_setting(), coverage_setting(), scene_triangles_setting(),
                                        adapt_triangles_setting()},
                                       {}};
    return source;
}

const OccluderSource &shadow_occluder_source()
{
    using Role = SettingSpec::Role;
    static const OccluderSource source{
        "shadow culling's large occluders",
        {
            integer_setting("occluders", 8, 1, 1 << 16, Role::cost,
                            "occluders per frame, by the solid-angle metric (Hudson et al.: about eight)"),
            on_off_setting("aggregate", true, Role::choice,
                           "each skin box whole, its faces that face the eye one occluder (Coorg and Teller's "
                           "aggregate); off: each face alone"),
        },
        {}};
    return source;
}

}  // namespace occu
