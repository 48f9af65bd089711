// SPDX-License-Identifier: MIT
// Occluder stacks (Poon and Wang, section 4.1): for each occludee, the
// occluders in front of it at each pixel of its footprint.
//
// The view's occludees are the nodes with more than `min_occludee_triangles`
// triangles (the paper's filter of "occludees containing only few
// primitives") none of whose leaves is visible; the candidate occluders are
// the visible leaves of at least `min_occluder_pixels` pixels (the paper's
// filter of "tiny occluders"). Both come from one ID buffer of the view.
//
// Stacks are built with the Occlusion Unit instead of depth sorting:
// occludees go in groups of up to 64 with disjoint footprints; the depth
// buffer holds each one's nearest depth over its footprint; for each
// candidate one verbose pass draws it alone, depth tested, with one tile
// per occludee, and the tiles' pixel lists are exactly the pixels where the
// candidate lies in front of each occludee (the paper's depth sorting, per
// pixel), with no frame read back per occluder.
//
// Footprints are the run-time tests' (camera/footprint.h) at the frame size
// the database serves, in map pixels: preprocessing chooses occluders for
// the rectangle that will be tested.
#pragma once

#include <cstdint>
#include <vector>

#include "camera/camera.h"
#include "geometry/pixel_rect.h"
#include "render/scene_renderer.h"
#include "spatial/hierarchy.h"

namespace occu {

struct Occludee {
    std::uint32_t node;
    PixelRect rect;    // map pixels
    float z_near;      // nearest window depth
    std::vector<std::vector<std::uint32_t>> stack;   // per rect pixel, row by row: occluders in front
};

struct StackOptions {
    int resolution = 128;          // map pixels each way
    int map_divisor = 4;           // frame pixels per map pixel (the run-time maps')
    std::uint32_t min_occludee_triangles = 20;
    std::uint32_t min_occluder_pixels = 4;
};

struct ViewOccluders {
    std::vector<Occludee> occludees;
    std::vector<std::uint32_t> candidates;     // leaves
    std::vector<std::uint32_t> pixels;         // per node: first-hit pixels in the view's ID buffer
    std::uint32_t passes = 0;                  // verbose passes run
};

// Needs a current context with GL_MESAX_occlusion_unit; draws into
// framebuffers of its own.
ViewOccluders build_occluder_stacks(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera,
                                    const StackOptions &options);

}  // namespace occu
