// SPDX-License-Identifier: MIT
// A scene with no occlusion: a flat field of small objects (issue 18,
// item 6), the counterpart of the city (scene/city.h). A grid of small
// boxes ("posts") on a ground plane, spaced far enough apart that, seen
// from above at the `overhead` route's angles (camera/route.h), no post
// hides any part of another: every leaf in the frustum that would show
// pixels alone shows them in the frame. Occlusion culling can only cost
// time here; what a strategy spends on this scene beyond view-frustum
// culling is its overhead, which the adaptive switch-off
// (traversal/policies.h) exists to remove.
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace occu {

struct FieldOptions {
    int count_x = 128, count_z = 128;   // posts in the grid
    float spacing = 3.0f;               // metres, centre to centre
    float post_size = 0.8f;             // metres, the posts' footprint (square)
    float min_height = 0.5f, max_height = 1.0f;   // metres
    std::uint32_t seed = 2026;
};

// Deterministic for given options. Each post is a box (12 triangles), so
// the defaults make 196,610 triangles with the ground (a quad), about the 231,000
// that vfc draws of the city on its open route. The posts are the scene's
// 2.5D occluders (Scene::prism_occluders): each is a solid box.
//
// Why nothing hides anything from above: a box is convex, so no face of a
// post hides another face of it; two posts' footprints are at least
// spacing - post_size = 2.2 m apart horizontally (the defaults), and a
// point of one post is hidden by another only if the view ray from it,
// rising at angle a above the horizon towards the eye, passes over the
// other within height h <= max_height, that is within h / tan(a)
// horizontally. So nothing is hidden where every view ray descends more
// steeply than atan(1.0 / 2.2) = 24.4 degrees; the overhead route's rays
// all descend at 26.6 degrees or more (camera/route.h). The integration
// test no_occlusion_field_test.cpp checks it with the oracle.
Scene generate_field(const FieldOptions &options);

}  // namespace occu
