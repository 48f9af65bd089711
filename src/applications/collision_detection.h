// SPDX-License-Identifier: MIT
// Collision detection with occlusion tiles: Bartz, Meissner and Huettner,
// "Extending Graphics Hardware For Occlusion Queries In OpenGL" (1998),
// section 5, "Support for Collision Detection", and figure 7.
//
// The paper: "For a given position of the user, an image of the scene is
// generated. [...] in case the user heads in viewing direction - e.g.
// straight, straight-left - a subdivision of screen space can be
// determined which represents the possible collision areas within the
// viewport" (figure 7: 3 x 3 tiles, straight-up-left ... straight-down-
// right). "To check whether a certain step will cause a collision, a
// customized view-frustum covering the check area of the screen is
// rendered in GL_BRIEF_OCCLUSION mode. The far plane of this view-frustum
// depends on the step size of the user, near plane is identical to the
// view plane. [...] If the number of non-occlusion hits is different from
// the number of projection hits, some pixels of the customized
// view-frustum are occluded, which means that a collision can be
// expected. [...] backface culling must be disabled, in order to detect
// intersections with the backfacing polygons of the view-frustum."
// "testing backward stepping does require two-pass rendering since no
// image of the scene behind the user is available in the framebuffer."
//
// How occu reads it:
//
//  * The check volume of a step of length s is the camera's view frustum
//    truncated between its near plane n (the "view plane": what lies
//    nearer is clipped from the image, so neither check below sees it)
//    and a far plane at view depth s (measured from the eye along the
//    view direction, the direction the paper's user heads in). So
//    n < s < the camera's far plane, or the volume is empty (refused).
//  * Of the volume's six faces only the far one can fail a depth test:
//    the near face lies on the near plane, in front of everything the
//    depth buffer can hold (every one of its fragments passes: NOHC = PHC,
//    no information), and the four side faces contain the eye, so they
//    project edge-on onto the viewport's border and produce no fragments.
//    The far face covers every pixel of the viewport once, at the window
//    depth of view depth s; where the frame holds something nearer
//    (geometry inside the volume, seen at that pixel) its fragment fails
//    the depth test (GL_LESS: geometry exactly at s counts as a collision).
//    So the GL check draws the far face alone, a quad over the viewport,
//    in one GL_BRIEF_OCCLUSION_MESAX pass whose 9 occlusion tiles are
//    figure 7's split of the viewport: per tile PHC is the tile's pixel
//    count and NOHC the pixels free up to the step; NOHC != PHC is the
//    paper's "collision can be expected" in that heading. Seen from the
//    eye, the far face of a closed volume wound outwards is a back face
//    (the paper's "backfacing polygons of the view-frustum"): the check
//    turns culling off for its pass, whatever the caller's state.
//  * The scene's back faces must be in the depth buffer too: a wall seen
//    from behind, or every face of a building the eye has walked into, is
//    as solid for collisions as a front face. A frame drawn with back
//    faces culled (as walkthrough draws it) misses them; draw the frame
//    with draw_collision_frame (culling off) before a forward check.
//  * Forward steps test the frame bound when check() is called: the depth
//    buffer of the camera's view, drawn by the caller (the paper's "image
//    of the scene", reused). Backward steps are the paper's second pass:
//    the camera turned round (same eye and up, opposite view direction),
//    drawn into a framebuffer of the check's own (gl/framebuffer.h) of
//    the caller's viewport size, and tested there. The second pass draws
//    only the leaves whose boxes meet the check volume (through the
//    hierarchy): a leaf wholly outside it puts fragments only beyond the
//    far plane (where they cannot make the far face fail), outside the
//    frustum or in front of the near plane (clipped), so the counts are
//    those of drawing every leaf in the frustum, for a fraction of the
//    cost. check_own_pass() does the same for a forward step (a program
//    with no frame of that view); the tests check that it counts exactly
//    what the frame does.
//  * Tiles are named by the screen of the view that is checked: in a
//    backward check the turned camera's left is the walker's right.
//  * The volume is the view's, not the walker's body: from an eye at
//    height h over a floor, with a vertical field of view fovy, the floor
//    enters the down tiles once the step exceeds h / tan(fovy / 2) (2.94 m
//    at 1.7 m and 60 degrees) and the middle row once it exceeds three
//    times that (8.8 m). Both methods call that a collision, as the
//    paper's test does: "collision can only be indicated".
//
// The exact reference (ExactCollisionTest): the same volume, per tile the
// sub-frustum through the eye and the tile's pixel edges (the tile's whole
// pixel area, in double precision), against every triangle of the leaves
// whose boxes meet the volume, each triangle clipped by the six planes
// (closed half-spaces: touching counts). Where the two may legitimately
// differ, and how explain() tells:
//  * Pixel sampling: the GL sees geometry only at pixel centres. A
//    triangle that enters a tile's volume between pixel centres (a box
//    corner poking a few millimetres past the far plane, a sliver at a
//    tile's edge, geometry thinner than a pixel, a degenerate triangle)
//    is a collision for the exact test and free for the GL: a false
//    negative of the GL check, sub-pixel.
//  * Depth precision at the far plane (and the near plane): window depth
//    is 24-bit, interpolated in float, and the scene's vertices go through
//    float matrices, so geometry within step_depth_tolerance() of the far
//    (or near) plane may land on either side.
//  * Back faces: none, when the frame is drawn with draw_collision_frame;
//    with a frame drawn culled, every back face in the volume is a false
//    negative of the GL check.
//  * Geometry in front of the near plane (closer than n to the eye) is in
//    neither volume: both are blind there (the paper: "collision
//    detection can only be indicated and depends on the given viewport").
//
// Both need fixed-function drawing (no program bound), as all of occu's
// drawing does, and GL_MESAX_occlusion_unit (gl/occlusion_unit.h).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "camera/camera.h"
#include "geometry/pixel_rect.h"
#include "gl/framebuffer.h"
#include "gl/occlusion_unit.h"
#include "render/scene_renderer.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"

namespace occu {

// Figure 7's subdivision of screen space: 3 x 3 tiles, numbered row by row
// from the top left as the figure shows them (0 straight-up-left, 4
// straight, 8 straight-down-right).
constexpr int collision_tile_count = 9;
const char *heading_name(int tile);
// The tiles of `viewport` (window pixels, y up, so row 0 of the figure is
// the highest third): column and row edges at round(k w / 3), round(k h / 3).
std::array<PixelRect, collision_tile_count> heading_tiles(const PixelRect &viewport);

enum class StepDirection { forward, backward };
const char *step_direction_name(StepDirection direction);
// The view a step is checked in: `camera` forward; backward, `camera`
// turned round (same eye, near and far planes and up, opposite view direction).
Camera check_camera(const Camera &camera, StepDirection direction);

// The check volume of a step of `step_length` metres: check_camera's
// frustum between its near plane and view depth step_length, and its nine
// tiles' sub-frusta for a viewport of width x height pixels. Planes are in
// world space, in double precision, normals pointing inwards (a point p is
// inside when dot(n, p) + w >= 0 for every plane). `margin` moves the near
// plane that much nearer the eye and the far plane that much farther
// (explain() grows the volume by the depth tolerance). Throws
// std::invalid_argument unless near_plane < step_length < far_plane,
// step_length is finite and the viewport has at least 3 x 3 pixels (one
// per tile).
class StepVolume {
public:
    StepVolume(const Camera &camera, double step_length, StepDirection direction, int width, int height,
               double margin = 0.0);

    const Camera &camera() const { return camera_; }   // check_camera
    double near_depth() const { return near_; }
    double far_depth() const { return far_; }
    int width() const { return width_; }
    int height() const { return height_; }
    // Near, far, left, right, bottom, top of the whole volume.
    const std::array<glm::dvec4, 6> &planes() const { return planes_; }
    // Left, right, bottom, top of tile k's sub-frustum (its near and far
    // planes are the volume's).
    const std::array<glm::dvec4, 4> &tile_planes(int k) const { return tile_planes_[std::size_t(k)]; }
    // The view and projection matrices the GL uses (camera's, in double).
    const glm::dmat4 &view() const { return view_; }
    const glm::dmat4 &projection() const { return projection_; }
    // Normalized device z of the far plane with the camera's projection:
    // where the GL check draws the far face.
    double far_ndc_z() const;

private:
    Camera camera_;
    double near_, far_;
    int width_, height_;
    glm::dmat4 view_, projection_;
    std::array<glm::dvec4, 6> planes_;
    std::array<std::array<glm::dvec4, 4>, collision_tile_count> tile_planes_;
};

// The leaves whose boxes meet `volume` (not outside any of its six
// planes), found from the root down; in node order.
std::vector<std::uint32_t> leaves_within_reach(const Hierarchy &hierarchy, const StepVolume &volume);

// How far (metres of view depth) from the far or near plane of the check
// volume geometry may fall on either side in the GL check: 24-bit depth,
// float interpolation and float vertex transforms (derived in the .cpp).
double step_depth_tolerance(const Camera &camera, double step_length);

// One tile of a GL check.
struct TileCheck {
    std::uint32_t nohc = 0;   // far-face fragments that passed the depth test: pixels free up to the step
    std::uint32_t phc = 0;    // far-face fragments: the tile's pixels
    bool collides = false;    // nohc != phc, the paper's test
};

struct CollisionResult {
    std::array<TileCheck, collision_tile_count> tiles;
    bool any() const;
};

// Draws the frame of `camera` as the forward check wants it: clears colour
// and depth, then every leaf in the frustum with back faces drawn (culling
// off for the call; depth test on, GL_LESS). Leaves the camera loaded.
void draw_collision_frame(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera);

// The GL check (needs a current context with GL_MESAX_occlusion_unit:
// throws std::runtime_error otherwise).
class CollisionCheck {
public:
    CollisionCheck(const SceneRenderer &renderer, const Hierarchy &hierarchy);

    // Forward: tests the depth buffer of the framebuffer bound now, which
    // must hold the frame of `camera` (draw_collision_frame), in its
    // viewport. Backward: the second pass, in the check's own framebuffer
    // of the viewport's size. Throws std::invalid_argument as StepVolume.
    // The caller's framebuffer, bindings, viewport, matrices and state are
    // as they were.
    CollisionResult check(const Camera &camera, float step_length, StepDirection direction);
    // Either direction in the check's own framebuffer, drawing the leaves
    // within reach of the step (what check() does backwards).
    CollisionResult check_own_pass(const Camera &camera, float step_length, StepDirection direction);

    // Leaves the last own pass drew.
    std::size_t last_pass_leaves() const { return last_pass_leaves_; }

private:
    CollisionResult test_far_face(const StepVolume &volume, const PixelRect &viewport);

    gl::OcclusionUnit unit_;
    const SceneRenderer &renderer_;
    const Hierarchy &hierarchy_;
    std::optional<gl::Framebuffer> target_;
    std::size_t last_pass_leaves_ = 0;
};

// Why a tile's GL answer and exact answer differ (ExactCollisionTest::explain).
enum class Agreement {
    agree,
    sub_pixel,         // exact collision, GL free: no pixel centre of the tile sees the geometry within the step
    depth_precision,   // the geometry deciding it lies within step_depth_tolerance of the far or near plane
    unexplained,       // neither: a defect
};
const char *agreement_name(Agreement a);

// The exact CPU reference of the same step.
class ExactCollisionTest {
public:
    ExactCollisionTest(const Scene &scene, const Hierarchy &hierarchy);

    // Per tile: does a triangle meet the tile's sub-frustum of the check
    // volume (a viewport of width x height pixels)? Throws as StepVolume.
    std::array<bool, collision_tile_count> check(const Camera &camera, float step_length, StepDirection direction,
                                                 int width, int height) const;
    std::array<bool, collision_tile_count> check(const StepVolume &volume) const;

    // Per tile, why `gl` and `exact` (this test's answer for the same step
    // and viewport) differ. Exact collision, GL free: sub_pixel when no
    // pixel centre's ray meets geometry of the volume (grown by the depth
    // tolerance), depth_precision when the rays meet it only within the
    // tolerance of the far or near plane, else unexplained. GL collision,
    // exact free: depth_precision when the volume grown by the tolerance
    // meets a triangle, else unexplained. Casts rays in double, only in
    // the tiles that differ.
    std::array<Agreement, collision_tile_count> explain(const Camera &camera, float step_length,
                                                        StepDirection direction, int width, int height,
                                                        const CollisionResult &gl,
                                                        const std::array<bool, collision_tile_count> &exact) const;

private:
    template <class Visit>
    void for_each_triangle(const StepVolume &volume, Visit &&visit) const;

    const Scene &scene_;
    const Hierarchy &hierarchy_;
};

}  // namespace occu
