// SPDX-License-Identifier: MIT
#include "evaluation/scene_setup.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "camera/route.h"
#include "scene/pk3_archive.h"
#include "scene/scene_file.h"
#include "spatial/inside_points.h"

namespace occu {

namespace {

std::shared_ptr<const Scene> make_scene(const SceneChoice &choice)
{
    // An unreadable file is named before assimp's own words about it; a
    // level in a pk3 archive is no file of its own: load_scene names what
    // is missing.
    std::string archive, member;
    if (!generated_scene_name(choice.name) && !split_pk3_path(choice.name, archive, member) &&
        !std::ifstream(choice.name))
        throw std::runtime_error("cannot read scene '" + choice.name + "'" +
                                 (std::filesystem::exists(choice.name) ? "" : ": no such file"));
    return std::make_shared<const Scene>(scene_by_name(choice.name, choice.city, choice.quake3));
}

}  // namespace

SceneSetup::SceneSetup(const SceneChoice &choice)
    : SceneSetup(choice.name.empty() ? "city" : choice.name, choice.city, make_scene(choice), choice.hierarchy)
{
}

SceneSetup::SceneSetup(Scene scene, const HierarchyOptions &options, std::string name)
    : SceneSetup(std::move(name), CityOptions{}, std::make_shared<const Scene>(std::move(scene)), options)
{
}

SceneSetup::SceneSetup(std::string name, const CityOptions &city, std::shared_ptr<const Scene> scene,
                       const HierarchyOptions &hierarchy)
    : name_(std::move(name)), city_(city), scene_(std::move(scene)),
      hierarchy_(std::make_shared<const Hierarchy>(Hierarchy::build(*scene_, hierarchy)))
{
}

SceneSetup SceneSetup::with_hierarchy(const HierarchyOptions &options) const
{
    return SceneSetup(name_, city_, scene_, options);
}

EyeTest SceneSetup::eye_inside() const
{
    // A level has its open leaves; the city and the field are generated
    // with streets and gaps to stand in. A model read from a file is a
    // building or an object: random eyes go inside it.
    if (scene_->level || generated_scene_name(name_))
        return {};
    const std::shared_ptr<const Scene> scene = scene_;
    const std::shared_ptr<const Hierarchy> hierarchy = hierarchy_;
    return [scene, hierarchy](const glm::vec3 &p) { return inside_model(*scene, *hierarchy, p); };
}

std::vector<Camera> SceneSetup::route(const std::string &route, int frames, float aspect) const
{
    return make_route(route, scene_->bounds, city_, frames, aspect, scene_->level.get(), eye_inside());
}

std::vector<Camera> SceneSetup::random_views(long count, unsigned long seed, float fov_min, float fov_max,
                                             float aspect) const
{
    return occu::random_views(scene_->bounds, count, seed, aspect, fov_min, fov_max, scene_->level.get(),
                              eye_inside());
}

}  // namespace occu
