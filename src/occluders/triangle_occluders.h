// SPDX-License-Identifier: MIT
// The scene's own triangles as occluders in a CPU depth buffer
// (raster/depth_rasterizer.h), for meshes with no volume for skins (thin
// walls, open meshes; occluders/skin_occluders.h): those of occluder
// meshes only, chosen per frame by projected area, the largest first up
// to a budget (occluder-triangles; with adapt-triangles, as many as the
// last frame's added to the buffer, adapted_budget), and rasterized by the same
// conservative rasterizer as skins, as Intel's Masked Occlusion Culling
// takes a game's own meshes. A front-facing triangle in the frustum is
// drawn by GL wherever nothing nearer hides it, and what hides it hides
// what lies behind it, so its farthest depth over a fully covered depth
// pixel is a safe occluder (Leone, section 3: occluders fuse in the
// buffer). A triangle across the near plane is clipped there by the
// rasterizer (the part GL draws), never dropped nor taken whole.
//
// Choosing does not look at every triangle every frame. A triangle's
// score is twice its projected area in normalized device coordinates; the
// corners' clip (x, y, w) are M (p - e) for the eye e and the 3 x 3 matrix
// M of the view-projection's x, y and w rows, so that area is
// det M (n . (p0 - e)) / (w0 w1 w2), n the triangle's normal twice its
// world area long. Over a box beyond the near plane it is therefore at most
// |det M| times twice the world area times the box's farthest distance
// from the eye over its nearest w cubed: a bound that holds for every
// slant, field of view and place on or off the screen. The triangles are
// grouped by the hierarchy's leaves, each group ranked by world area, and
// every node keeps its subtree's largest; a frame starts from the
// triangles it chose last time (frames are coherent, so the budget's
// smallest score is high at once), then opens the hierarchy's nodes in
// the frustum best bound first (a node's children bounded and classified
// eight at a time, occluders/choice_kernels.h), and stops at the first node, and within a
// leaf at the first triangle, whose bound cannot beat the budget's
// smallest score. A leaf's triangles are scored eight at a time
// (occluders/choice_kernels.h), with every test that does not depend on
// the scores chosen so far; a triangle facing away, or whose own plane
// bounds it below that score, is then dropped one by one. The chosen
// ones are the budget's best by score. Which triangles are chosen decides
// only how much is culled, never whether it is safe: every one drawn is a
// triangle GL draws.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "culling/culler.h"
#include "culling/settings.h"
#include "occluders/choice_kernels.h"
#include "raster/depth_rasterizer.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"

namespace occu {

class TriangleOccluders {
public:
    // As the settings ask (occluders/sources.h, triangle_occluder_source):
    // occluder-triangles, the budget (0, or a family without the setting:
    // none), at least `least_budget`, and with coverage=merged the
    // triangle across each edge. Grouped by `hierarchy`'s leaves where
    // given (null: one group of all). Keeps `scene` and `hierarchy` by
    // reference.
    TriangleOccluders(const Scene &scene, const Settings &settings, std::size_t least_budget = 0,
                      const Hierarchy *hierarchy = nullptr);

    // Renders into `raster` at most budget() of the scene's occluder
    // triangles that face the eye in `frame`'s frustum, the largest
    // projected area first, drawn nearest first. Returns how many it drew.
    // With adapt-triangles, the budget of the frames after follows what
    // this one's drawing showed (adapted_budget).
    std::size_t render(const Frame &frame, DepthRasterizer &raster);
    // What render() draws for `frame`: three indices into corners() a
    // triangle, nearest first. Valid until the next call.
    const std::vector<std::uint32_t> &choose(const Frame &frame);
    // The occluder triangles' corners, three a triangle.
    const std::vector<glm::vec3> &corners() const { return corners_; }
    // The budget the next frame chooses up to.
    std::size_t budget() const { return budget_; }
    // adapt-triangles: the next frame's budget when `reached` of the
    // triangles drawn this frame reached past what the buffer held before
    // them (DepthRasterizer::Stats::rasterized: with merged coverage,
    // those not behind everything already there), within [least, most]:
    // five quarters of `reached`, rounded up. Drawn nearest first, a
    // triangle that does not reach past the buffer adds nothing to it.
    // Where more than four in five of the chosen do (open ground, where
    // the skins hide little) the budget grows, by a quarter a frame at
    // most, up to `most`; where fewer do (the skins and the nearest
    // triangles hide the rest: a city's streets) it shrinks towards
    // `least`. So it is Zhang et al. 1997's adaptive occluder count (the
    // hom family's adapt-budget: more occluders while little is culled,
    // fewer while much is), with the
    // share of the chosen that add to the buffer in place of the share of
    // the tested that is culled, a share the buffer knows before the
    // tests; and it reads no clock, so a route's frames are the same
    // every run. Which triangles are drawn decides only how much is
    // culled: every one is a triangle GL draws.
    static std::size_t adapted_budget(std::size_t reached, std::size_t least, std::size_t most);
    // The least budget adapt-triangles shrinks to (the setting's, where
    // smaller; scene-triangles' least, where larger). On the city's
    // streets the skins hide nearly all that the triangles would: 64
    // triangles cull what 128 do there, to a thousandth of a point.
    static constexpr std::size_t adapted_least = 64;

private:
    struct Group {
        std::uint32_t first = 0, count = 0;   // in corners_ / 3, the largest world area first
        std::uint32_t slot = 0;               // its first in arrays_
    };
    // What opening a hierarchy node takes, kept by node so that offer()
    // reads a node's children side by side: a leaf's group, or for an
    // inner node its children (first, count) and slot inner_node. The
    // choice reads no HierarchyNode, whose scattered reads cost a cache
    // miss a node opened.
    static constexpr std::uint32_t inner_node = ~0u;
    struct Opening {
        float largest = 0.0f;   // its subtree's largest twice world area (0: no occluder triangle)
        Group group;
    };
    // A node to open, or a leaf to scan: the most a triangle in it may
    // score, and the frustum planes its box reaches across.
    struct Candidate {
        float bound;
        Group open;   // as Opening's
        unsigned planes;
        float per_area, nearest_w;   // bound_per_area's, for a leaf's scan
    };
    struct Chosen {
        float score;
        std::uint32_t triangle, slot;   // in corners_ / 3, in arrays_
        float nearest_w;                // its corners' smallest clip w
    };
    // The most a triangle in `box` may score, over its twice world area;
    // `nearest_w` is the box's nearest clip w.
    float bound_per_area(const Aabb &box, float &nearest_w) const;
    // Keeps triangle t (at `slot` in arrays_), of `score` (twice its projected area, the header's
    // formula; choice::score_lanes), if it is among the best so far.
    void take(float score, std::uint32_t t, std::uint32_t slot, float nearest_w);
    // The triangles of group g, largest first, while they may beat the
    // budget's smallest score; per_area and nearest_w are bound_per_area's
    // for the group's box.
    void scan(const Group &g, float per_area, float nearest_w, unsigned planes);
    // Asks the cache for what opening the best candidate will read: the
    // scan's first block of eight triangles, or the children's boxes.
    void prefetch_best() const;
    // Offers the nodes first .. first + count - 1 (siblings) to open, those
    // in the frustum that may beat the budget's smallest score, bounded
    // and classified eight at a time (choice::bound_boxes); `planes`: the
    // frustum planes their parent reaches across.
    void offer(std::uint32_t first, std::uint32_t count, unsigned planes);
    bool full() const { return chosen_.size() == budget_; }
    float smallest_chosen() const { return chosen_.front().score; }

    const Hierarchy *hierarchy_ = nullptr;
    std::size_t budget_ = 0;
    // adapt-triangles: the bounds of budget_ (both budget_ without it).
    std::size_t least_budget_ = 0, most_budget_ = 0;
    Aabb bounds_;                      // of every occluder triangle
    std::vector<glm::vec3> corners_;   // 3 per triangle, grouped
    choice::TriangleArrays arrays_;    // in blocks of eight: normals twice the world area long, corners, twice areas
    choice::TriangleLanes lanes_;
    decltype(&choice::score_lanes_scalar) score_lanes_ = choice::score_lanes_scalar;   // AVX2 where the CPU has it
    std::vector<Group> groups_;
    std::vector<Opening> openings_;           // per hierarchy node
    std::vector<float> node_box_coordinates_;   // the nodes' boxes by coordinate (node_boxes_), 8 floats' padding each
    choice::BoxArrays node_boxes_{};
    decltype(&choice::bound_boxes_scalar) bound_boxes_ = choice::bound_boxes_scalar;   // AVX2 where the CPU has it
    std::vector<glm::vec3> across_;   // coverage=merged: 3 per triangle (shared_edge_opposites)
    // Per frame: the best so far, a min-heap by score, then nearest first;
    // the nodes to open, a max-heap by bound; the corners' indices drawn
    // and the triangles across them. Between frames: the triangles chosen
    // last, their arrays_ lanes copied in that order (scored again first
    // thing next frame: eight at a time from consecutive memory rather
    // than gathered from wherever they lie in arrays_, a cache miss a
    // field), and a mark on each while it is being taken again.
    choice::ChoiceView view_;
    std::vector<Chosen> chosen_;
    std::vector<Candidate> candidates_;
    std::vector<std::uint32_t> drawn_indices_;
    std::vector<glm::vec3> drawn_across_;
    std::vector<std::uint32_t> last_chosen_, last_slots_;
    std::vector<float> last_chosen_blocks_;
    std::vector<std::uint8_t> taken_again_;
};

}  // namespace occu
