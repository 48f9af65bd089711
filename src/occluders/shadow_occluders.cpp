// SPDX-License-Identifier: MIT
// Occluders of shadow culling per frame: see shadow_occluders.h.
#include "occluders/shadow_occluders.h"

#include <algorithm>
#include <cmath>

#include "geometry/convex_region.h"

namespace occu {

namespace {

// Coorg and Teller's solid-angle estimate g = -a (n . v) / (d . d) of
// face f of `box` (the chapter, "Shadow Culling", figure 11); 0 when the
// face does not face the eye (or lies within the margin of its plane).
double face_score(const Aabb &box, int f, const glm::dvec3 &eye, const glm::dvec3 &view, double margin)
{
    const int a = f / 2, u = (a + 1) % 3, v = (a + 2) % 3;
    const glm::dvec3 n = box_face_normal(f);
    glm::dvec3 centre = 0.5 * (glm::dvec3(box.min) + glm::dvec3(box.max));
    centre[a] = f % 2 ? box.max[a] : box.min[a];
    if (!(glm::dot(n, eye - centre) > margin))
        return 0.0;
    const double area = (double(box.max[u]) - box.min[u]) * (double(box.max[v]) - box.min[v]);
    const glm::dvec3 d = centre - eye;
    return std::max(0.0, -area * glm::dot(n, view) / std::max(glm::dot(d, d), 1e-12));
}

}  // namespace

ShadowOccluders::ShadowOccluders(const Scene &scene, const Settings &settings)
    : skins_(scene, settings), aggregate_(settings.on("aggregate"))
{
    was_chosen_.assign(id_limit(), 0);
}

const std::vector<ShadowOccluder> &ShadowOccluders::choose(const Frame &frame, std::size_t count)
{
    const Camera &camera = frame.camera;
    const glm::dvec3 eye(camera.position);
    const glm::dvec3 view = glm::normalize(glm::dvec3(camera.target) - eye);
    const auto &boxes = skins_.boxes();
    ranked_.clear();
    for (std::uint32_t b = 0; b < boxes.size(); ++b) {
        const Aabb &box = boxes[b];
        if (frame.frustum.classify(box) == Frustum::Side::outside || !skins_.usable(b, frame))
            continue;
        const double margin = shadow_margin(std::max(magnitude(eye), magnitude(box)));
        auto rank = [&](const ShadowOccluder &o) {
            if (o.score > 0.0)
                ranked_.emplace_back(o.score * (was_chosen_[o.id] ? keep_factor : 1.0), o);
        };
        if (aggregate_) {
            ShadowOccluder o{b * 7 + 6, b, -1, 0.0};
            for (int f = 0; f < 6; ++f)
                o.score += face_score(box, f, eye, view, margin);
            rank(o);
        } else {
            for (int f = 0; f < 6; ++f)
                rank(ShadowOccluder{b * 7 + std::uint32_t(f), b, f, face_score(box, f, eye, view, margin)});
        }
    }
    auto better = [](const auto &x, const auto &y) { return x.first > y.first || (x.first == y.first && x.second.id < y.second.id); };
    if (ranked_.size() > count) {
        std::nth_element(ranked_.begin(), ranked_.begin() + std::ptrdiff_t(count), ranked_.end(), better);
        ranked_.resize(count);
    }
    std::sort(ranked_.begin(), ranked_.end(), better);
    for (std::uint32_t id : last_ids_)
        was_chosen_[id] = 0;
    last_ids_.clear();
    chosen_.clear();
    for (const auto &r : ranked_) {
        chosen_.push_back(r.second);
        last_ids_.push_back(r.second.id);
        was_chosen_[r.second.id] = 1;
    }
    return chosen_;
}

}  // namespace occu
