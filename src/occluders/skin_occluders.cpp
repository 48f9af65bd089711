// SPDX-License-Identifier: MIT
#include "occluders/skin_occluders.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <stdexcept>

#include "occluders/occluder_skins.h"
#include "occluders/sources.h"
#include "scene/level.h"

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

}  // namespace

SkinOccluders::SkinOccluders(const Scene &scene, const std::string &database, int boxes_per_mesh,
                             const SkinOptions &options)
    : scene_(&scene)
{
    for (const Mesh &m : scene.meshes)
        if (m.occluder)
            occluder_triangles_ += m.triangle_count();
    auto keep = [&](std::uint32_t mesh, const std::vector<Aabb> &boxes) {
        // A see-through mesh hides nothing, whatever a database says.
        if (mesh >= scene.meshes.size() || !scene.meshes[mesh].occluder)
            return;
        if (!boxes.empty() && boxes_per_mesh > 0)
            skinned_triangles_ += scene.meshes[mesh].triangle_count();
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

double SkinOccluders::share_without_skins() const
{
    if (brushes_)
        return boxes_.empty() ? 1.0 : 0.0;
    if (occluder_triangles_ == 0)
        return 1.0;
    return 1.0 - double(skinned_triangles_) / double(occluder_triangles_);
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
    if (!brushes_)
        return true;
    // LevelBrushOccluders::BoxBrush: a ray from the eye enters the box through a
    // side whose outer half-space holds the eye, and must meet a drawn face
    // there or before.
    if (!brush_occluders_.box_brushes[i].hides_from(frame.camera.position, brush_occluders_.opaque_brushes))
        return false;
    return eye_clear(frame);
}

bool SkinOccluders::eye_clear(const Frame &frame) const
{
    if (frame.view_projection == clear_view_projection_)
        return clear_;
    clear_view_projection_ = frame.view_projection;
    clear_ = false;
    const glm::dvec3 eye(frame.camera.position);
    if (scene_->level) {
        const std::int32_t leaf = scene_->level->leaf_at(frame.camera.position);
        if (leaf < 0 || scene_->level->leaves[std::size_t(leaf)].cluster < 0)
            return false;   // in a solid or outside the level
    }
    // The near rectangle's farthest corner from the eye: every point of
    // the frustum nearer than the near plane lies within it.
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(frame.view_projection));
    double reach = 0.0;
    for (int c = 0; c < 4; ++c) {
        const glm::dvec4 p = inverse * glm::dvec4(c & 1 ? 1.0 : -1.0, c & 2 ? 1.0 : -1.0, -1.0, 1.0);
        if (!(std::abs(p.w) > 0.0))
            return false;
        reach = std::max(reach, glm::length(glm::dvec3(p) / p.w - eye));
    }
    if (!std::isfinite(reach))
        return false;
    reach = reach * 1.01 + 1e-4;
    for (const Aabb &b : solids_) {
        const glm::dvec3 d = glm::max(glm::max(glm::dvec3(b.min) - eye, eye - glm::dvec3(b.max)), glm::dvec3(0.0));
        if (glm::dot(d, d) <= reach * reach)
            return false;
    }
    clear_ = true;
    return true;
}

SkinOccluders::SkinOccluders(const Scene &scene, const Settings &settings)
    : SkinOccluders(scene, settings.text("skin-database"), int(settings.integer("skin-boxes")), skin_options(settings))
{
    if (settings.text("skin-source") == "brushes") {
        // Leone et al., section 4: occluders made by hand are the best; a
        // level's designer made its solids as brushes.
        if (!scene.level)
            throw std::runtime_error("skin-source=brushes: the scene is not a Quake III level (it has no brushes)");
        brush_occluders_ = level_brush_occluders(scene);
        boxes_.clear();
        for (const LevelBrushOccluders::BoxBrush &box : brush_occluders_.box_brushes)
            boxes_.push_back(box.bounds);
        mesh_bounds_ = boxes_;
        solids_ = scene.level->solid_brush_bounds;
        brushes_ = true;
    }
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
