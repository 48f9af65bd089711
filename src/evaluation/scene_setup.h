// SPDX-License-Identifier: MIT
// The scene a program measures, made in one place for every program and
// test: its meshes (the procedural city, the field, or a file), the
// hierarchy built over them (spatial/hierarchy.h) and the routes through
// them (camera/route.h). Scene and hierarchy are shared by the copies of a
// setup, and stay where they are for as long as one copy lives, so that a
// renderer or a strategy made over them may hold on to them.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "camera/route.h"
#include "scene/city.h"
#include "scene/quake3_bsp.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"

namespace occu {

// What a program's --scene (and its hierarchy options) name.
struct SceneChoice {
    // "city" (or empty): the procedural city of `city` (scene/city.h);
    // "field": the flat field of small objects (scene/field.h); a Quake III
    // level, PAK.pk3:maps/NAME.bsp or a .bsp file (scene/quake3_bsp.h, read
    // with `quake3`); anything else a file (scene/scene_file.h).
    std::string name = "city";
    CityOptions city;
    Quake3Options quake3;
    HierarchyOptions hierarchy;

    SceneChoice() = default;
    // A program's --scene, --city-copies and --leaf-triangles.
    SceneChoice(std::string scene, int city_copies, std::uint32_t leaf_triangles) : name(std::move(scene))
    {
        city.copies = city_copies;
        hierarchy.max_leaf_triangles = leaf_triangles;
    }
};

class SceneSetup {
public:
    // Generates or reads the scene, then builds its hierarchy. Throws
    // std::runtime_error naming a scene file it cannot read (and saying
    // when there is no such file) or whose contents it refuses.
    explicit SceneSetup(const SceneChoice &choice);
    // A scene made by the caller (a test's own), named `name`, under a
    // hierarchy of `options`; its random eyes lie inside its model, as a
    // file's do.
    SceneSetup(Scene scene, const HierarchyOptions &options, std::string name = "scene");
    // The same scene under a hierarchy of other options (a leaf size swept).
    SceneSetup with_hierarchy(const HierarchyOptions &options) const;

    // As the choice named it ("city" for the default).
    const std::string &name() const { return name_; }
    const Scene &scene() const { return *scene_; }
    const Hierarchy &hierarchy() const { return *hierarchy_; }

    // The route `route` (camera/route.h: dense, street, medium, open, orbit,
    // overhead, spawn on a level, random:N:SEED or a route file) of `frames`
    // cameras; on a level, random eyes lie in its open leaves, in a model
    // read from a file inside it (spatial/inside_points.h); throws as
    // make_route does.
    std::vector<Camera> route(const std::string &route, int frames, float aspect = 1.0f) const;
    // `count` random views (camera/route.h: random_views), each with a field
    // of view in [fov_min, fov_max] degrees.
    std::vector<Camera> random_views(long count, unsigned long seed, float fov_min, float fov_max,
                                     float aspect = 1.0f) const;

private:
    // Where random eyes may stand: inside the model for a scene read from
    // a file that is not a level; empty (anywhere, or a level's own test)
    // otherwise.
    EyeTest eye_inside() const;
    SceneSetup(std::string name, const CityOptions &city, std::shared_ptr<const Scene> scene,
               const HierarchyOptions &hierarchy);
    std::string name_;
    CityOptions city_;   // the routes of the city are laid out along its streets
    std::shared_ptr<const Scene> scene_;
    std::shared_ptr<const Hierarchy> hierarchy_;
};

}  // namespace occu
