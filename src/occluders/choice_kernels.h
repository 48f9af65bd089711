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

namespace occu::choice {

// The triangles by coordinate: normal (twice the world area long), the
// three corners, twice the world area. Each array holds `lane_padding`
// floats past the last triangle, so that eight lanes may be loaded from
// any triangle.
constexpr std::size_t lane_padding = 8;
struct TriangleLanes {
    const float *normal[3];
    const float *corner[3][3];   // [corner][axis]
    const float *twice_area;
};

// The same, owned: add() in order, then finish().
class TriangleArrays {
public:
    void add(const glm::vec3 *corners, const glm::vec3 &normal, float twice_area);
    void finish();
    TriangleLanes lanes() const;
    std::size_t size() const { return size_; }

private:
    std::size_t size_ = 0;
    std::vector<float> normal_[3], corner_[3][3], twice_area_;
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

// Scores `count` (at most 8) triangles: first .. first + count - 1, or
// where `gather` is given, gather[0 .. count - 1]. `planes`: bit i tests
// view.planes[i]. Lanes from `count` on are not kept.
void score_lanes_scalar(const TriangleLanes &t, const std::uint32_t *gather, std::uint32_t first, int count,
                        const ChoiceView &view, unsigned planes, LaneScores &out);
void score_lanes_avx2(const TriangleLanes &t, const std::uint32_t *gather, std::uint32_t first, int count,
                      const ChoiceView &view, unsigned planes, LaneScores &out);

}  // namespace occu::choice
