// A scene with no occlusion: a flat field of small objects (issue 18,
// item 6), the counterpart of the city (scene/city.h). A grid of small
// posts, each a box with a ledge around it (the city's facade detail in
// small, so that a post costs triangles to draw), on a ground plane, spaced
// far enough apart that, seen from above at the `overhead` route's angles
// (camera/route.h), no post hides any part of another: every leaf in the
// frustum shows. Occlusion culling can only cost time here; what a
// strategy spends on this scene beyond view-frustum culling is its
// overhead, which the adaptive switch-off (traversal/policies.h) exists to
// remove.
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace occu {

struct FieldOptions {
    int count_x = 64, count_z = 64;   // posts in the grid
    float spacing = 6.0f;             // metres, centre to centre
    float post_size = 1.6f;           // metres, the posts' footprint (square)
    float ledge_depth = 0.2f;         // metres, how far the ledge sticks out
    float min_height = 1.0f, max_height = 1.8f;   // metres
    std::uint32_t seed = 2026;
};

// Deterministic for given options. Each post has 60 triangles (its box and
// a ledge of four boxes halfway up, 0.2 m deep), so the defaults make
// 245,772 triangles, about the city's 272,796. The posts are the scene's
// 2.5D occluders (Scene::prism_occluders): each is a solid box.
//
// Why nothing hides anything from above: two posts' footprints, ledges
// included, are at least spacing - post_size - 2 ledge_depth = 4.0 m apart
// horizontally (the defaults), and a point of one post is hidden by another
// only if the view ray from it, rising at angle a above the horizon towards
// the eye, passes over the other within height h <= max_height, that is
// within h / tan(a) horizontally. So nothing is hidden where every view ray
// descends more steeply than atan(1.8 / 4.0) = 24.2 degrees; the overhead
// route's rays all descend at 26.6 degrees or more (camera/route.h). The
// integration test no_occlusion_field_test.cpp checks it with the oracle.
Scene generate_field(const FieldOptions &options);

}  // namespace occu
