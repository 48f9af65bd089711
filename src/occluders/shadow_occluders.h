// SPDX-License-Identifier: MIT
// The occluders of object-space shadow culling (Moeller and Haines,
// "Occlusion Culling Algorithms", section "Shadow Culling": "select a
// small set of large occluders and discard the objects behind [them]"),
// shared by the `shadow` strategy (Hudson et al.) and the `planes`
// strategy (Coorg and Teller): occluders/sources.h, shadow_occluder_source.
//
// Occluders are large planar convex polygons: the faces of the scene's
// occluder skins (occluders/skin_occluders.h; boxes
// inside each mesh), one quad each, or (aggregate) each skin box whole, its
// faces that face the eye acting as one occluder (Coorg and Teller's
// aggregate occluders: polygons sharing edges;
// strategies/hudson_shadow_frusta/shadow_frusta.h for its
// shadow).
//
// Per frame, over the skins in the view frustum: a face counts when it
// faces the eye; it is scored by Coorg and Teller's estimate of the solid
// angle it subtends, g = -a (n . v) / (d . d) (a its area, n its outward
// normal, v the unit view direction, d from the eye to its centre), a box
// aggregate by the sum of its front faces' positive g; the best `count`
// are kept. Temporal coherence (Hudson et al.: "an occluder that was good
// ... for one frame is probably good ... the next frame too"): last
// frame's occluders have their score doubled in the ranking, so one is
// replaced only by an occluder more than twice as good, and a set that
// stays good does not flicker as the eye moves.
//
// Conservative use: a skin stands for its mesh only where the mesh's
// bounding box lies wholly beyond the near plane (SkinOccluders::usable):
// a ray from the eye to a point behind the skin then crosses the mesh's
// surface before the skin, at a face that faces the eye, which GL draws in
// front of the point.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "culling/culler.h"
#include "occluders/skin_occluders.h"
#include "scene/scene.h"

namespace occu {

struct ShadowOccluder {
    std::uint32_t id = 0;    // box * 7 + face, box * 7 + 6 for the whole box
    std::uint32_t box = 0;   // index into boxes()
    int face = -1;           // 0..5 (geometry/convex_region.h's box_face), -1: the box aggregate
    double score = 0.0;      // g, summed over the front faces of an aggregate
};

class ShadowOccluders {
public:
    // The skins as the strategy's settings ask (occluders/sources.h,
    // shadow_occluder_source and skin_occluder_source):
    // aggregate=on, boxes whole, else their faces.
    ShadowOccluders(const Scene &scene, const Settings &settings);

    // The frame's occluders, the best first: at most `count`.
    const std::vector<ShadowOccluder> &choose(const Frame &frame, std::size_t count);

    const std::vector<Aabb> &boxes() const { return skins_.boxes(); }
    bool aggregate() const { return aggregate_; }
    // Occluder ids are below this.
    std::size_t id_limit() const { return skins_.boxes().size() * 7; }

    // Ranking: last frame's occluders' scores are multiplied by this.
    static constexpr double keep_factor = 2.0;

private:
    SkinOccluders skins_;
    bool aggregate_;
    std::vector<char> was_chosen_;   // by id, last frame's
    std::vector<std::uint32_t> last_ids_;
    std::vector<std::pair<double, ShadowOccluder>> ranked_;
    std::vector<ShadowOccluder> chosen_;
};

}  // namespace occu
