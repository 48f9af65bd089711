#include "occluders/skin_occluders.h"

#include <algorithm>
#include <stdexcept>

#include "preprocessing/occluder_skins.h"

namespace occu {

SkinOccluders::SkinOccluders(const Scene &scene, const std::string &database, int boxes_per_mesh)
{
    auto keep = [&](const std::vector<Aabb> &boxes) {
        for (std::size_t i = 0; i < boxes.size() && i < std::size_t(boxes_per_mesh); ++i)
            boxes_.push_back(boxes[i]);
    };
    if (database.empty()) {
        for (const MeshSkins &m : scene_skins(scene, SkinOptions{}).skins)
            keep(m.boxes);
        return;
    }
    const OccluderSkinDatabase db = OccluderSkinDatabase::load(database);
    const std::string mismatch = db.provenance.mismatch_for(scene);
    if (!mismatch.empty())
        throw std::runtime_error(database + ": " + mismatch);
    for (const auto &[mesh, boxes] : db.skins)
        keep(boxes);
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
        if (frame.frustum.classify(b) == Frustum::Side::outside)
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
    for (const auto &c : chosen_)
        raster.render_box(boxes_[c.second]);
    return chosen_.size();
}

}  // namespace occu
