#include "strategies/leone_occluder_skins/skin_occluders.h"

#include <algorithm>
#include <map>
#include <mutex>
#include <stdexcept>

#include "strategies/leone_occluder_skins/occluder_skins.h"

namespace occu {

namespace {

// Skins made at start, once per scene and options for all the strategies
// of a process (a walkthrough compares several on one scene).
const SceneSkins &skins_of(const Scene &scene, const SkinOptions &options)
{
    static std::mutex lock;
    static std::map<std::string, SceneSkins> made;
    const std::lock_guard<std::mutex> guard(lock);
    const std::string key = scene_geometry_fingerprint(scene) + " " + options.describe();
    auto it = made.find(key);
    if (it == made.end())
        it = made.emplace(key, scene_skins(scene, options)).first;
    return it->second;
}

SkinOptions skin_options(const Settings &settings)
{
    SkinOptions options;
    options.voxel_size = float(settings.number("skin-voxel"));
    return options;
}

}  // namespace

SkinOccluders::SkinOccluders(const Scene &scene, const std::string &database, int boxes_per_mesh,
                             const SkinOptions &options)
{
    auto keep = [&](std::uint32_t mesh, const std::vector<Aabb> &boxes) {
        // A see-through mesh hides nothing, whatever a database says.
        if (mesh >= scene.meshes.size() || !scene.meshes[mesh].occluder)
            return;
        Aabb bounds;
        for (const glm::vec3 &p : scene.meshes[mesh].positions)
            bounds.expand(p);
        for (std::size_t i = 0; i < boxes.size() && i < std::size_t(boxes_per_mesh); ++i) {
            boxes_.push_back(boxes[i]);
            mesh_bounds_.push_back(bounds);
        }
    };
    if (database.empty()) {
        for (const MeshSkins &m : skins_of(scene, options).skins)
            keep(m.mesh, m.boxes);
        return;
    }
    const OccluderSkinDatabase db = OccluderSkinDatabase::load(database);
    const std::string mismatch = db.provenance.mismatch(skin_scene_provenance(scene));
    if (!mismatch.empty())
        throw std::runtime_error(database + ": " + mismatch);
    for (const auto &[mesh, boxes] : db.skins)
        keep(mesh, boxes);
}

bool SkinOccluders::usable(std::size_t i, const Frame &frame) const
{
    // View depth along the camera's axis, which is what the near plane
    // clips (camera/camera.h: the view looks from position to target),
    // in double, with a margin above the near distance for the rounding of
    // GL's clip test.
    const glm::dvec3 eye(frame.camera.position);
    const glm::dvec3 forward = glm::normalize(glm::dvec3(frame.camera.target) - eye);
    const double near = double(frame.camera.near_plane) * (1.0 + 1e-5) + 1e-6;
    const Aabb &m = mesh_bounds_[i];
    for (int c = 0; c < 8; ++c)
        if (!(glm::dot(glm::dvec3(m.corner(c)) - eye, forward) > near))
            return false;
    return true;
}

SkinOccluders::SkinOccluders(const Scene &scene, const Settings &settings)
    : SkinOccluders(scene, settings.text("skin-database"), int(settings.integer("skin-boxes")), skin_options(settings))
{
}

std::vector<SettingSpec> skin_settings()
{
    return {
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

std::size_t SkinOccluders::render(const Frame &frame, DepthRasterizer &raster, std::size_t limit)
{
    // The solid angle a box subtends, up to a constant: its squared extent
    // over its squared distance (Poon and Wang's projected size; Leone's
    // "best candidates", section 3).
    chosen_.clear();
    const glm::vec3 eye = frame.camera.position;
    for (std::size_t i = 0; i < boxes_.size(); ++i) {
        const Aabb &b = boxes_[i];
        if (frame.frustum.classify(b) == Frustum::Side::outside || !usable(i, frame))
            continue;
        const glm::vec3 d = glm::max(glm::max(b.min - eye, eye - b.max), glm::vec3(0.0f));
        const float extent = glm::dot(b.extent(), b.extent());
        chosen_.emplace_back(extent / std::max(glm::dot(d, d), 1e-6f), std::uint32_t(i));
    }
    if (limit && chosen_.size() > limit) {
        std::nth_element(chosen_.begin(), chosen_.begin() + std::ptrdiff_t(limit), chosen_.end(),
                         [](const auto &a, const auto &b) { return a.first > b.first; });
        chosen_.resize(limit);
    }
    // Nearest first, and a skin already hidden by those before it is not
    // drawn: in a street most skins stand behind the first few, and
    // filling their pixels would change nothing (occluders fuse in the
    // buffer, section 3, so the hidden ones add no occlusion).
    for (auto &c : chosen_) {
        const Aabb &b = boxes_[c.second];
        const glm::vec3 d = glm::max(glm::max(b.min - eye, eye - b.max), glm::vec3(0.0f));
        c.first = glm::dot(d, d);
    }
    std::sort(chosen_.begin(), chosen_.end());
    std::size_t drawn = 0;
    for (const auto &c : chosen_) {
        const Aabb &b = boxes_[c.second];
        const auto footprint = frame.footprint(b);
        if (footprint && raster.occluded(footprint->rect, footprint->window_z_near))
            continue;
        raster.render_box(b);
        ++drawn;
    }
    return drawn;
}

}  // namespace occu
