// SPDX-License-Identifier: MIT
// The occluder triangles' choice (occluders/triangle_occluders.h), eight
// triangles at a time: each one's score and every rejection that does not
// depend on the scores chosen so far (facing away, no area, wholly behind
// one frustum plane), once in scalar code and once in AVX2. Both evaluate
// the same float expressions in the same order as the header's formula is
// written there, without fused multiply-add (their files build with
// -ffp-contract=off), so their results are equal bit for bit, and a
// triangle's score is the one a triangle-at-a-time evaluation gives.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "memory/large_buffers.h"

namespace occu::choice {

// The triangles in blocks of eight slots, each field's eight lanes side
// by side (13 x 8 floats a block: the normal, twice the world area long,
// the three corners, twice the world area), so that a batch of eight reads
// as few cache lines as the triangles themselves would. A group of
// triangles starts a block; the slots past its end are zeros.
constexpr int fields = 13;
enum Field { normal_x = 0, corner0_x = 3, corner1_x = 6, corner2_x = 9, twice_area = 12 };
constexpr std::size_t block_floats = std::size_t(fields) * 8;
struct TriangleLanes {
    const float *blocks;
    float at(int field, std::uint32_t slot) const { return blocks[slot / 8 * block_floats + std::size_t(field) * 8 + slot % 8]; }
};

// Copies slot `from` of `t` to slot `to` of `blocks`, laid out as
// TriangleLanes' and holding that slot's block.
inline void copy_slot(const TriangleLanes &t, std::uint32_t from, float *blocks, std::uint32_t to)
{
    const float *source = t.blocks + from / 8 * block_floats + from % 8;
    float *target = blocks + to / 8 * block_floats + to % 8;
    for (int field = 0; field < fields; ++field)
        target[field * 8] = source[field * 8];
}

// The same, owned: start_group(), its triangles' add() in order, ...,
// then finish(). The blocks lie on 2 MiB pages where they fill one
// (memory/large_buffers.h): a frame's choice jumps from leaf to leaf across
// megabytes of blocks (the city's 270 000 triangles: 14 MB), which with
// 4 KiB pages costs a TLB miss, a page walk, nearly every leaf.
class TriangleArrays {
public:
    // Returns the group's first slot.
    std::uint32_t start_group();
    void add(const glm::vec3 *corners, const glm::vec3 &normal, float twice_area);
    void finish();
    TriangleLanes lanes() const { return {blocks_.data()}; }
    // The slot of the t-th triangle added.
    std::uint32_t slot(std::uint32_t t) const { return slot_of_[t]; }
    std::size_t size() const { return slot_of_.size(); }

private:
    std::uint32_t slots_ = 0;
    LargeBuffer<float> blocks_;
    std::vector<std::uint32_t> slot_of_;
};

// What a frame's scores read: clip w = w_row . (p, 1); the frustum's
// planes (normals inwards, as Frustum::planes()).
struct ChoiceView {
    glm::vec3 eye;
    glm::vec4 w_row;
    float area_scale;   // -det M of the view-projection's x, y, w rows
    float near;
    glm::vec4 planes[6];
};

// Eight triangles' results, lane i for triangle i of the batch.
struct LaneScores {
    float score[8];       // twice the projected area, or the solid angle's stand-in across the near plane
    float most[8];        // area_scale (n . (e - p0)): beyond the near plane, the score times w0 w1 w2
    float nearest_w[8];   // the corners' smallest clip w
    unsigned keep;        // bit i: lane i faces the eye, has a finite score above 0, and is behind none of `planes`
};

// Scores `count` (at most 8) triangles: the slots first .. first + count
// - 1 (first a multiple of 8), or where `gather` is given, the slots
// gather[0 .. count - 1]. `planes`: bit i tests view.planes[i]. Lanes
// from `count` on are not kept.
void score_lanes_scalar(const TriangleLanes &t, const std::uint32_t *gather, std::uint32_t first, int count,
                        const ChoiceView &view, unsigned planes, LaneScores &out);
void score_lanes_avx2(const TriangleLanes &t, const std::uint32_t *gather, std::uint32_t first, int count,
                      const ChoiceView &view, unsigned planes, LaneScores &out);

// Boxes coordinate by coordinate (a hierarchy's nodes: min x, y, z, then
// max x, y, z, each an array by node), and eight of them at once: what
// TriangleOccluders::bound_per_area bounds a triangle's score in each by,
// over its twice world area, and the box's nearest clip w; and the box
// classified against the frustum as Frustum::classify(box, crossing)
// classifies it, with the same float expressions in the same order.
struct BoxArrays {
    const float *min[3], *max[3];
};
struct LaneBounds {
    float per_area[8];
    float nearest_w[8];
    unsigned outside;       // bit i: box i lies wholly behind one of the planes tested
    unsigned crossing[8];   // Frustum::classify's `crossing` on return, box by box
};
// The boxes first .. first + count - 1 (count at most 8; the arrays
// readable up to first + 8), each tested against the planes in `planes`
// (bit i: view.planes[i]).
void bound_boxes_scalar(const BoxArrays &b, std::uint32_t first, int count, const ChoiceView &view, unsigned planes,
                        LaneBounds &out);
void bound_boxes_avx2(const BoxArrays &b, std::uint32_t first, int count, const ChoiceView &view, unsigned planes,
                      LaneBounds &out);

}  // namespace occu::choice
