// SPDX-License-Identifier: MIT
// A box's footprint on screen: the one box-to-rectangle function of occu,
// used alike by the run-time tests (every strategy) and by preprocessing,
// so that what preprocessing chooses occluders for is what is tested.
//
// Convention: window pixels of a viewport of width x height, (0, 0) its
// lower left pixel (geometry/pixel_rect.h). The footprint is every pixel
// whose centre the box's projection can cover, grown by one pixel on each
// side for the rounding of float projection and rasterization, clipped to
// the viewport. A box that holds the eye or reaches in front of the near
// plane has no footprint (its projection is not bounded by its corners):
// callers take it as visible without a test.
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "camera/camera.h"
#include "geometry/pixel_rect.h"

namespace occu {

struct Footprint {
    PixelRect rect;        // viewport pixels; may be empty (the box projects outside the viewport)
    float window_z_near;   // the nearest window depth of the box's corners
};

std::optional<Footprint> box_footprint(const glm::mat4 &view_projection, const glm::vec3 &eye, const Aabb &box,
                                       int viewport_width, int viewport_height);

// box_footprint's two kernels, equal bit for bit (the footprints, and so
// every strategy's answers, do not depend on the CPU): project_box's
// corners and fold with std::floor and std::ceil, and the eight corners in
// one set of AVX2 lanes, folded in a tree and rounded with SSE4.1's
// roundps. box_footprint takes the AVX2 one where the CPU has it (it runs
// for every node every occlusion test tests); the AVX2 kernel only there.
std::optional<Footprint> box_footprint_scalar(const glm::mat4 &view_projection, const glm::vec3 &eye, const Aabb &box,
                                              int viewport_width, int viewport_height);
std::optional<Footprint> box_footprint_avx2(const glm::mat4 &view_projection, const glm::vec3 &eye, const Aabb &box,
                                            int viewport_width, int viewport_height);

}  // namespace occu
