// SPDX-License-Identifier: MIT
// Named hard cases for conservative culling: small scenes, each with one
// camera and viewport chosen to be numerically or geometrically awkward
// (the eye inside boxes, the near plane through them, far from the origin,
// extreme depth ranges and fields of view, coplanar and degenerate
// geometry, viewports of one pixel and of millions, a leaf of a million
// triangles). In each, every conservative strategy of the registry and
// every test variant its family declares (culling/registry.h) loses no
// visible pixel against the unculled frame, as the measurement session
// counts them (evaluation/lost_pixels.h), as on the city's routes
// (conservative_frames_test.cpp). Strategies that require a database get
// one made by the database provider (culling/databases.h) for each case's
// scene and viewport, as small as their settings allow (common settings
// of one grid point and four headings where a strategy has them); a
// family that refuses a case's scene must refuse to be made for it.
// Runs on the driver meson selects with GALLIUM_DRIVER.
//
// Each case first checks the premise that makes it the case it is named
// for (the eye is inside a leaf's box, a box crosses the near plane, ...),
// so that a change of the fixture cannot quietly turn it into an easy one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <filesystem>
#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "culling/databases.h"
#include "culling/registry.h"
#include "evaluation/measurement_session.h"
#include "evaluation/oracle.h"
#include "gl/offscreen_context.h"
#include "scene/scene.h"
#include "spatial/hierarchy.h"

#include "strategy_variants.h"

using namespace occu;

namespace {

// Scenes of boxes and loose triangles, each object a mesh of its own
// colour, so that losing any object changes pixels.
class SceneBuilder {
public:
    // Every vertex is placed at offset + its coordinates, rounded to float
    // once (the scene's own coordinates are floats, as everywhere in occu).
    explicit SceneBuilder(const glm::dvec3 &offset = glm::dvec3(0.0)) : offset_(offset) {}

    void box(const glm::dvec3 &min, const glm::dvec3 &max)
    {
        append_box(next_mesh(), Aabb::of(place(min), place(max)));
    }

    // Counter-clockwise seen from the front; degenerate ones are kept.
    void triangle(const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c)
    {
        Mesh &m = next_mesh();
        const glm::vec3 p[3] = {place(a), place(b), place(c)};
        const glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
        const float length = glm::length(n);
        for (const glm::vec3 &v : p) {
            m.positions.push_back(v);
            m.normals.push_back(length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f));
        }
        m.indices = {0, 1, 2};
    }

    // Two triangles, a b c d counter-clockwise seen from the front.
    void quad(const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c, const glm::dvec3 &d)
    {
        triangle(a, b, c);
        triangle(a, c, d);
    }

    Scene build()
    {
        scene_.update_bounds();
        return std::move(scene_);
    }

private:
    glm::vec3 place(const glm::dvec3 &p) const { return glm::vec3(offset_ + p); }

    Mesh &next_mesh()
    {
        // Hues a golden-ratio step apart: neighbours in the list differ.
        const float hue = std::fmod(float(scene_.meshes.size()) * 0.618034f, 1.0f) * 6.0f;
        const glm::vec3 rgb = glm::clamp(glm::abs(glm::mod(glm::vec3(hue, hue + 4.0f, hue + 2.0f), 6.0f) - 3.0f) - 1.0f,
                                         0.0f, 1.0f);
        Mesh m;
        m.color = 0.25f + 0.75f * rgb;
        scene_.meshes.push_back(std::move(m));
        return scene_.meshes.back();
    }

    glm::dvec3 offset_;
    Scene scene_;
};

// Ground, a wall 3 m high and a crowd of 13 x 13 pillars 1 to 5 m high
// behind it, and two pillars in front: from eye height before the wall,
// the wall hides the pillars behind it while those beside it show, so
// strategies cull, and a wrong cull would change pixels.
void add_street(SceneBuilder &b)
{
    b.box({-30, -0.2, -40}, {30, 0, 10});   // ground
    b.box({-5, 0, -6.25}, {5, 3, -6});      // wall
    for (int i = 0; i < 13; ++i)
        for (int j = 0; j < 13; ++j) {
            const double x = -9 + 1.5 * i, z = -8 - 1.5 * j, height = 1 + (i * 7 + j * 3) % 5;
            b.box({x - 0.25, 0, z - 0.25}, {x + 0.25, height, z + 0.25});
        }
    b.box({-2.25, 0, -3.25}, {-1.75, 2, -2.75});
    b.box({1.75, 0, -3.25}, {2.25, 2, -2.75});
}

Scene street()
{
    SceneBuilder b;
    add_street(b);
    return b.build();
}

Camera camera(const glm::vec3 &position, const glm::vec3 &target, float near_plane = 0.1f, float far_plane = 100.0f)
{
    Camera c;
    c.position = position;
    c.target = target;
    c.near_plane = near_plane;
    c.far_plane = far_plane;
    return c;
}

// At eye height in front of the wall, looking down the street at it.
Camera street_camera()
{
    return camera({0, 1.5f, 2}, {0, 1.5f, -10});
}

// A gap among the pillars (they stand 1.5 m apart, 0.5 m wide), looking
// diagonally across the rows.
Camera camera_among_pillars(float near_plane = 0.1f)
{
    return camera({-6.75f, 1.5f, -17.75f}, {4, 1.5f, -27}, near_plane);
}

HierarchyOptions leaves_of(std::uint32_t triangles)
{
    HierarchyOptions o;
    o.max_leaf_triangles = triangles;
    return o;
}

using Premise = std::function<::testing::AssertionResult(const Hierarchy &, const Frame &)>;

struct HardCase {
    HardCase(Scene s, const Camera &c) : scene(std::move(s)), camera(c) {}

    Scene scene;
    Camera camera;
    int width = 128, height = 128;
    HierarchyOptions hierarchy = leaves_of(12);
    // The oracle sees some leaves of the frustum and not others: strategies
    // have something to cull, and something to keep.
    bool hides_leaves = true;
    // Nothing is in view: the unculled frame is all background.
    bool empty_frame = false;
    Premise premise;   // what makes the case the one it is named for
};

// --- premises ----------------------------------------------------------------------

::testing::AssertionResult eye_inside_a_leaf_box(const Hierarchy &h, const Frame &frame)
{
    for (const HierarchyNode &n : h.nodes())
        if (n.leaf() && n.bounds.contains(frame.camera.position))
            return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "no leaf's box holds the eye";
}

::testing::AssertionResult eye_inside_the_root_box_only(const Hierarchy &h, const Frame &frame)
{
    if (!h.root().bounds.contains(frame.camera.position))
        return ::testing::AssertionFailure() << "the root's box does not hold the eye";
    if (eye_inside_a_leaf_box(h, frame))
        return ::testing::AssertionFailure() << "a leaf's box holds the eye too";
    return ::testing::AssertionSuccess();
}

// A leaf in the frustum, not holding the eye, reaches in front of the near
// plane: it has no footprint, and strategies must take it as visible.
::testing::AssertionResult near_plane_cuts_a_leaf_box(const Hierarchy &h, const Frame &frame)
{
    for (const HierarchyNode &n : h.nodes())
        if (n.leaf() && !n.bounds.contains(frame.camera.position) &&
            frame.frustum.classify(n.bounds) != Frustum::Side::outside && !frame.footprint(n.bounds))
            return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "no leaf's box crosses the near plane";
}

// A leaf has corners both in front of the eye and behind it (clip w of
// both signs): its projection wraps through infinity.
::testing::AssertionResult a_leaf_crosses_the_eye_plane(const Hierarchy &h, const Frame &frame)
{
    const glm::mat4 view = frame.camera.view();
    for (const HierarchyNode &n : h.nodes()) {
        if (!n.leaf())
            continue;
        bool in_front = false, behind = false;
        for (int i = 0; i < 8; ++i) {
            const float z = (view * glm::vec4(n.bounds.corner(i), 1.0f)).z;
            in_front = in_front || z < 0.0f;
            behind = behind || z > 0.0f;
        }
        if (in_front && behind && frame.frustum.classify(n.bounds) != Frustum::Side::outside)
            return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "no leaf in the frustum crosses the eye plane";
}

::testing::AssertionResult a_leaf_box_has_zero_thickness(const Hierarchy &h, const Frame &frame)
{
    for (const HierarchyNode &n : h.nodes()) {
        const glm::vec3 e = n.bounds.extent();
        if (n.leaf() && (e.x == 0.0f || e.y == 0.0f || e.z == 0.0f) &&
            frame.frustum.classify(n.bounds) != Frustum::Side::outside)
            return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "no leaf in the frustum has a box of zero thickness";
}

// A leaf the oracle sees projects to less than a pixel each way.
::testing::AssertionResult a_visible_leaf_is_below_a_pixel(const Hierarchy &h, const Frame &frame)
{
    for (std::uint32_t leaf : frame.truth->visible) {
        const auto p = project_box(frame.view_projection, frame.camera.position, h.nodes()[leaf].bounds);
        if (p && (p->ndc_max.x - p->ndc_min.x) * 0.5f * float(frame.width) < 1.0f &&
            (p->ndc_max.y - p->ndc_min.y) * 0.5f * float(frame.height) < 1.0f)
            return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "no visible leaf is smaller than a pixel";
}

// --- the cases ---------------------------------------------------------------------

HardCase eye_inside_a_leaf_box_case()
{
    // Leaves of four pillars or so: their boxes span the gaps between them.
    HardCase c{street(), camera_among_pillars()};
    c.hierarchy = leaves_of(48);
    c.premise = eye_inside_a_leaf_box;
    return c;
}

HardCase eye_inside_the_root_box_case()
{
    // Leaves of one pillar each: the eye, in a gap, is in no leaf's box.
    HardCase c{street(), camera_among_pillars()};
    c.premise = eye_inside_the_root_box_only;
    return c;
}

HardCase near_plane_cuts_boxes_case()
{
    // The nearest pillars' boxes are 0.7 m from the eye, inside the near plane.
    HardCase c{street(), camera_among_pillars(0.9f)};
    c.premise = near_plane_cuts_a_leaf_box;
    return c;
}

HardCase geometry_crossing_the_eye_plane_case()
{
    // Walls along the street, from behind the eye to far ahead.
    SceneBuilder b;
    add_street(b);
    b.box({-3.25, 0, -30}, {-3, 2.5, 10});
    b.box({3, 0, -30}, {3.25, 2.5, 10});
    HardCase c{b.build(), street_camera()};
    c.premise = a_leaf_crosses_the_eye_plane;
    return c;
}

// World coordinates are floats throughout occu (vertices, boxes, the
// camera, the matrices) and in GL: a 24-bit significand leaves neighbouring
// floats 2^-7 m = 7.8 mm apart at 1e5 m from the origin and 2^-4 m = 6.25 cm
// apart at 1e6 m. The street's vertices round to that grid, and the view
// transform's cancellation (1e6 minus 1e6 in float) moves projected
// vertices by about as much: at 1e6 a few centimetres, a fraction of a
// pixel at the street's distances (9 cm at 10 m here). No strategy keeps
// more precision than that; what must hold is that boxes and the triangles
// they bound round alike, so that culling stays conservative. At 1e7 m
// floats are 1 m apart and this street's unculled frame is empty: a scene
// that far out holds only what lies on that grid (the metre-grid case
// below), and finer detail needs coordinates relative to a nearer origin.
HardCase translated_case(double offset)
{
    SceneBuilder b{glm::dvec3(offset)};
    add_street(b);
    HardCase c{b.build(), street_camera()};
    c.camera.position = glm::vec3(glm::dvec3(c.camera.position) + offset);
    c.camera.target = glm::vec3(glm::dvec3(c.camera.target) + offset);
    return c;
}

// At 1e7 m floats are 1 m apart: a street built on that grid (every
// coordinate a whole metre, so that its vertices and the camera are exact)
// is what a scene there can hold. The view transform still subtracts 1e7
// from 1e7 in float, rounding projected vertices by up to a metre's worth
// at the eye's distance (a pixel or two here); boxes and the triangles
// they bound round alike, so culling must stay conservative.
HardCase translated_metre_grid_case(double offset)
{
    SceneBuilder b{glm::dvec3(offset)};
    b.box({-40, -1, -60}, {40, 0, 20});   // ground
    b.box({-8, 0, -12}, {8, 6, -10});      // wall
    for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 6; ++j) {
            const double x = -16 + 4 * i, z = -16 - 4 * j, height = 2 + (i * 7 + j * 3) % 5;
            b.box({x - 1, 0, z - 1}, {x + 1, height, z + 1});
        }
    HardCase c{b.build(), camera({0, 3, 8}, {0, 3, -20}, 1.0f, 200.0f)};
    c.camera.position = glm::vec3(glm::dvec3(c.camera.position) + offset);
    c.camera.target = glm::vec3(glm::dvec3(c.camera.target) + offset);
    return c;
}

HardCase near_far_ratio_case(float near_plane)
{
    // Far plane 100 m: the depth buffer's 24 bits are spent near the eye.
    HardCase c{street(), street_camera()};
    c.camera.near_plane = near_plane;
    c.camera.far_plane = 100.0f;
    return c;
}

// Pillars behind the wall whose front faces lie in the wall's front face
// (z = -6): they z-fight with it below 3 m and show above it, and slabs
// wholly inside the wall's face, which show only where they win the fight.
Scene coplanar_faces()
{
    SceneBuilder b;
    add_street(b);
    for (double x : {-4.75, -3.0, -0.5, 1.0, 2.5, 4.75})
        b.box({x - 0.25, 0, -7}, {x + 0.25, 4, -6});
    for (double x : {-4.0, -2.0, 0.0, 2.0})
        b.box({x, 0.5, -6.5}, {x + 1.0, 2.5, -6});
    return b.build();
}

HardCase coplanar_faces_head_on_case()
{
    // The view axis is normal to the faces: every fragment of either has
    // the same depth, and the leaf drawn first keeps the pixel.
    return HardCase{coplanar_faces(), street_camera()};
}

HardCase coplanar_faces_obliquely_case()
{
    // Seen at an angle, the faces' depths differ by rounding from pixel to
    // pixel, each triangle interpolating its own corners.
    return HardCase{coplanar_faces(), camera({4, 2.5f, 0}, {-2, 1.5f, -8})};
}

HardCase sub_pixel_leaves_case()
{
    // Boxes of 20 cm 40 to 60 m away, where a pixel is 45 cm wide: a
    // layer 5 m up, hidden by the wall, and one 14 m up, above its shadow,
    // whose boxes cover some pixel centres and miss others.
    SceneBuilder b;
    add_street(b);
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 8; ++j)
            for (double y : {5.0, 14.0}) {
                const double x = -15 + 1.5 * i, z = -40 - 2.5 * j;
                b.box({x, y, z}, {x + 0.2, y + 0.2, z + 0.2});
            }
    HardCase c{b.build(), street_camera()};
    c.premise = a_visible_leaf_is_below_a_pixel;
    return c;
}

// A building seen corner-on a few hundred metres away, as the copied
// city's corner buildings are from a crossing: its two faces meet along
// the edge nearest the eye, along which depth pixels of several frame
// pixels are covered by neither face wholly, and at that distance the
// window depths of the building and of what stands 30 m behind it differ
// by about 1e-6, the size of the depth margins. A row of pillars behind
// the edge (hidden), one just in front of it and one beside the building
// (seen).
HardCase corner_on_far_from_the_eye_case()
{
    SceneBuilder b;
    b.box({-50, -1, -450}, {450, 0, 50});   // ground
    const double edge = 300.0 / std::sqrt(2.0);
    b.box({edge, 0, -edge - 40}, {edge + 40, 60, -edge});   // the building
    for (int i = 1; i <= 6; ++i) {
        const double at = edge + 8.0 * i + 45.0;   // along the diagonal, behind the building
        b.box({at - 1, 0, -at - 1}, {at + 1, 8, -at + 1});
    }
    const double front = edge - 4.0;
    b.box({front - 1, 0, -front - 1}, {front + 1, 3, -front + 1});
    b.box({edge - 30, 0, -edge + 10}, {edge - 28, 20, -edge + 12});
    HardCase c{b.build(), camera({0, 1.7f, 0}, {1, 1.7f, -1}, 0.5f, 4000.0f)};
    c.width = c.height = 256;
    c.hierarchy = leaves_of(12);
    return c;
}

HardCase zero_area_triangles_case()
{
    // Triangles with collinear corners and with a repeated corner, in
    // front of the wall, behind it and beside it: they cover no pixel, and
    // their boxes are lines.
    SceneBuilder b;
    add_street(b);
    for (int i = 0; i < 12; ++i) {
        const double x = -8 + 1.5 * i;
        for (double z : {-4.0, -9.0, -15.0}) {
            b.triangle({x, 0.5, z}, {x + 0.5, 1.0, z}, {x + 1.0, 1.5, z});
            b.triangle({x, 2.0, z}, {x, 2.0, z}, {x + 0.5, 2.5, z});
        }
    }
    return HardCase{b.build(), street_camera()};
}

HardCase zero_thickness_boxes_case()
{
    // Single-sided quads: facing the eye behind the wall (hidden) and
    // beside it (seen), lying on the ground, and one in the plane x = 0,
    // which holds the eye: seen edge on, it covers nothing. Leaves of two
    // triangles keep each quad's box flat.
    SceneBuilder b;
    add_street(b);
    for (double x : {-4.0, -1.0, 2.0, 6.5, -8.5})
        b.quad({x, 0.5, -10}, {x + 1.5, 0.5, -10}, {x + 1.5, 2.5, -10}, {x, 2.5, -10});
    b.quad({-1, 0.01, -1}, {1, 0.01, -1}, {1, 0.01, -3}, {-1, 0.01, -3});
    b.quad({0, 0.5, -2}, {0, 0.5, -4}, {0, 2, -4}, {0, 2, -2});
    HardCase c{b.build(), street_camera()};
    c.hierarchy = leaves_of(2);
    c.premise = a_leaf_box_has_zero_thickness;
    return c;
}

// Tables on the ground with a box under each, and canopies 6 m up with a
// box on each, on alternate cells of a grid among pillars: seen from
// above, tables and canopies hide what is under them; from below,
// canopies hide what is on them.
Scene tables_and_canopies()
{
    SceneBuilder b;
    b.box({-30, -0.2, -40}, {30, 0, 10});
    for (int i = -3; i <= 3; ++i)
        for (int j = -3; j <= 3; ++j) {
            const double x = 3.0 * i, z = -15 + 3.0 * j;
            if ((i + j) % 2 == 0) {
                b.box({x - 1, 1, z - 1}, {x + 1, 1.1, z + 1});
                b.box({x - 0.3, 0, z - 0.3}, {x + 0.3, 0.5, z + 0.3});
            } else {
                b.box({x - 1, 6, z - 1}, {x + 1, 6.1, z + 1});
                b.box({x - 0.3, 6.1, z - 0.3}, {x + 0.3, 6.6, z + 0.3});
            }
            b.box({x + 1.25, 0, z + 1.25}, {x + 1.5, 4, z + 1.5});
        }
    return b.build();
}

HardCase looking_straight_down_case()
{
    // The default up vector (+y) is parallel to the view direction.
    HardCase c{tables_and_canopies(), camera({0, 20, -15}, {0, 0, -15})};
    c.premise = [](const Hierarchy &, const Frame &frame) {
        const glm::vec3 view = glm::normalize(frame.camera.target - frame.camera.position);
        return glm::length(glm::cross(view, frame.camera.up)) == 0.0f
                   ? ::testing::AssertionSuccess()
                   : ::testing::AssertionFailure() << "the up vector is not parallel to the view direction";
    };
    return c;
}

HardCase looking_straight_up_case()
{
    // Under a canopy, with a field of view of 120 degrees that takes in the
    // canopies around it.
    HardCase c = looking_straight_down_case();
    c.camera = camera({0, 0.5f, -12}, {0, 20, -12});
    c.camera.fovy_degrees = 120.0f;
    // The pillars' vertical edges project onto the image's diagonal,
    // through pixel centres: the oracle must rasterize them as the frame
    // does (softpipe covers such a centre in one framebuffer orientation and
    // not in the other; the oracle draws into the frame's framebuffer).
    return c;
}

HardCase field_of_view_case(float degrees, int viewport_size = 128)
{
    HardCase c{street(), street_camera()};
    c.width = c.height = viewport_size;
    c.camera.fovy_degrees = degrees;
    if (degrees < 10.0f) {
        // 300 m back, 1 degree spans 5 m: the wall and the pillars above it.
        c.camera = camera({0, 1.5f, 300}, {0, 2.5f, -10}, 1.0f, 1000.0f);
        c.camera.fovy_degrees = degrees;
    } else {
        // Just before the wall: it hides the crowd behind it, and nearly
        // the whole half-space ahead is in view.
        c.camera.position = {0, 1.5f, -4};
    }
    return c;
}

HardCase viewport_case(int size)
{
    HardCase c{street(), street_camera()};
    c.width = c.height = size;
    return c;
}

HardCase empty_frustum_case()
{
    // Past the end of the ground, looking away from the street.
    HardCase c{street(), camera({0, 1.5f, 12}, {0, 1.5f, 30})};
    c.hides_leaves = false;
    c.empty_frame = true;
    return c;
}

HardCase one_triangle_case()
{
    SceneBuilder b;
    b.triangle({-1, 0.5, -5}, {1, 0.5, -5}, {0, 2.5, -5});
    HardCase c{b.build(), street_camera()};
    c.hides_leaves = false;
    return c;
}

// A million triangles in one leaf: each spans the same cube corner to
// corner, its third corner anywhere inside, so every triangle's box is the
// cube, and the octree, which splits by the centres of the triangles' boxes
// (spatial/hierarchy.h), cannot separate them: they stay one leaf. The blob
// stands behind the wall, hidden: strategies must cull a leaf whose drawing
// costs as much as a city block, and draw the street around it as before.
HardCase one_leaf_of_a_million_triangles_case()
{
    Scene scene = street();
    Mesh blob;
    blob.color = {0.9f, 0.3f, 0.2f};
    const glm::vec3 centre{0.5f, 1.0f, -7.5f}, half{0.4f};
    std::uint32_t state = 2026;
    auto unit = [&state] {   // a small deterministic generator, in [-1, 1)
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1 << 23) - 1.0f;
    };
    const std::size_t count = 1000000;
    blob.positions.reserve(3 * count);
    for (std::size_t i = 0; i < count; ++i) {
        const glm::vec3 corners[3] = {centre - half, centre + half,
                                      centre + half * glm::vec3(unit(), unit(), unit())};
        const glm::vec3 n = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
        for (const glm::vec3 &p : corners) {
            blob.positions.push_back(p);
            blob.normals.push_back(glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 1, 0));
            blob.indices.push_back(std::uint32_t(blob.indices.size()));
        }
    }
    blob.update_bounds();
    scene.meshes.push_back(std::move(blob));
    scene.update_bounds();
    HardCase c{std::move(scene), street_camera()};
    c.premise = [](const Hierarchy &h, const Frame &) -> ::testing::AssertionResult {
        std::uint32_t most = 0;
        for (const HierarchyNode &n : h.nodes())
            if (n.leaf())
                most = std::max(most, n.triangle_count);
        if (most >= 1000000)
            return ::testing::AssertionSuccess();
        return ::testing::AssertionFailure() << "no leaf holds the million triangles (the largest holds " << most << ")";
    };
    return c;
}

// A wall, and behind it a fence of 32 triangles, hidden, among which a
// larger triangle, a spike, reaches over the wall: in leaves of up to 40
// triangles one leaf holds the fence and the spike, and is seen only
// through the spike. A strategy that tests a leaf by groups of its
// triangles (the skins family's clusters, each with its box) must keep
// the spike in its group's box.
HardCase one_triangle_of_a_hidden_leaf_peeks_out_case()
{
    SceneBuilder b;
    b.box({-5, 0, -6.25}, {5, 3, -6});   // the wall
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 2; ++j) {
            const double x = 0.5 + 0.5 * i, y = 1.6 + 0.5 * j;
            b.quad({x, y, -7}, {x + 0.5, y, -7}, {x + 0.5, y + 0.5, -7}, {x, y + 0.5, -7});
        }
    // The line of sight over the wall's top (3 m at z = -6) meets z = -7 at
    // 3.19 m. The octree splits around the centre of its triangles' boxes'
    // centres (spatial/hierarchy.h), here x = 0, y = 1.5, z = -6.5: the
    // fence and the spike lie on one side of each.
    b.triangle({3.8, 1.6, -7}, {4.2, 1.6, -7}, {4.0, 5.0, -7});
    HardCase c{b.build(), street_camera()};
    c.hierarchy = leaves_of(40);
    c.hides_leaves = false;
    const std::uint32_t spike = std::uint32_t(c.scene.meshes.size() - 1);   // the last mesh
    c.premise = [spike](const Hierarchy &h, const Frame &frame) -> ::testing::AssertionResult {
        for (std::uint32_t i = 0; i < h.nodes().size(); ++i) {
            const HierarchyNode &n = h.nodes()[i];
            if (!n.leaf())
                continue;
            for (std::uint32_t t = n.first_triangle; t < n.first_triangle + n.triangle_count; ++t)
                if (h.triangles()[t].mesh == spike) {
                    if (n.triangle_count <= 16)
                        return ::testing::AssertionFailure()
                               << "the spike's leaf holds only " << n.triangle_count << " triangles";
                    if (!std::binary_search(frame.truth->visible.begin(), frame.truth->visible.end(), i))
                        return ::testing::AssertionFailure() << "the oracle does not see the spike's leaf";
                    return ::testing::AssertionSuccess();
                }
        }
        return ::testing::AssertionFailure() << "no leaf holds the spike";
    };
    return c;
}

HardCase all_triangles_in_one_point_case()
{
    // A thousand triangles with every corner at one point: the hierarchy's
    // boxes are that point, and nothing covers a pixel.
    SceneBuilder b;
    for (int i = 0; i < 1000; ++i)
        b.triangle({0.5, 1.5, -5}, {0.5, 1.5, -5}, {0.5, 1.5, -5});
    HardCase c{b.build(), street_camera()};
    c.hides_leaves = false;
    c.empty_frame = true;
    return c;
}

struct NamedCase {
    const char *name;
    std::function<HardCase()> make;
};

// How gtest prints a case's parameter: by its name.
void PrintTo(const NamedCase &c, std::ostream *out)
{
    *out << c.name;
}

const std::vector<NamedCase> hard_cases = {
    {"EyeInsideALeafBox", eye_inside_a_leaf_box_case},
    {"EyeInsideTheRootBoxOnly", eye_inside_the_root_box_case},
    {"NearPlaneCutsBoxes", near_plane_cuts_boxes_case},
    {"GeometryCrossingTheEyePlane", geometry_crossing_the_eye_plane_case},
    {"SceneTranslated1e5", [] { return translated_case(1e5); }},
    {"SceneTranslated1e6", [] { return translated_case(1e6); }},
    {"SceneTranslated1e7OnItsMetreGrid", [] { return translated_metre_grid_case(1e7); }},
    {"NearFarRatio1eMinus4", [] { return near_far_ratio_case(1e-2f); }},
    {"NearFarRatio1eMinus6", [] { return near_far_ratio_case(1e-4f); }},
    {"CornerOnBuildingFarFromTheEye", corner_on_far_from_the_eye_case},
    {"CoplanarOccluderAndOccludeeFacesHeadOn", coplanar_faces_head_on_case},
    {"CoplanarOccluderAndOccludeeFacesObliquely", coplanar_faces_obliquely_case},
    {"SubPixelLeaves", sub_pixel_leaves_case},
    {"ZeroAreaTriangles", zero_area_triangles_case},
    {"ZeroThicknessBoxes", zero_thickness_boxes_case},
    {"CameraLookingStraightDown", looking_straight_down_case},
    {"CameraLookingStraightUp", looking_straight_up_case},
    {"FieldOfView1Degree", [] { return field_of_view_case(1.0f); }},
    {"FieldOfView170Degrees", [] { return field_of_view_case(170.0f); }},
    {"Viewport1x1", [] { return viewport_case(1); }},
    // A pixel is 0.7 m wide at 1 m: proxies grow by more than their distance.
    {"FieldOfView170DegreesIn32x32", [] { return field_of_view_case(170.0f, 32); }},
    {"Viewport2048x2048", [] { return viewport_case(2048); }},
    {"Viewport4096x4096", [] { return viewport_case(4096); }},
    {"OneLeafOfAMillionTriangles", one_leaf_of_a_million_triangles_case},
    {"OneTriangleOfAHiddenLeafPeeksOut", one_triangle_of_a_hidden_leaf_peeks_out_case},
    {"EmptyFrustum", empty_frustum_case},
    {"SceneOfOneTriangle", one_triangle_case},
    {"AllTrianglesInOnePoint", all_triangles_in_one_point_case},
};

// What a strategy is given to make the databases it requires small: a
// database made for the frame size, of one view per heading.
const std::vector<std::string> small_databases = {"database-grid=1", "database-layers=1", "database-headings=4"};

bool requires_a_database(const StrategyChoice &choice)
{
    const auto read = databases_read(choice);
    return std::any_of(read.begin(), read.end(), [](const DatabaseNeed *d) { return d->required; });
}

// Every conservative strategy of the registry and every test variant its
// family declares (strategy_variants.h). The maps of the strategies that
// require a database made for the frame size are kept at most 128 pixels
// wide (a divisor above their own on large viewports), so that making the
// database of a 4096-pixel case stays a test's work; which map they use
// changes what is culled, never whether the frame may lose a pixel.
std::vector<StrategyTestVariant> hard_case_variants(int width)
{
    std::vector<StrategyTestVariant> variants = integration::conservative_test_variants();
    for (StrategyTestVariant &v : variants) {
        const StrategyChoice choice = choose_strategy(v.spec);
        if (requires_a_database(choice) && choice.settings.knows("map-divisor")) {
            const long divisor = std::max(choice.settings.integer("map-divisor"), long(width + 127) / 128);
            v.spec += ":map-divisor=" + std::to_string(divisor);
        }
    }
    return variants;
}

bool all_background(const std::uint8_t *pixels, std::size_t bytes)
{
    return std::all_of(pixels, pixels + bytes, [](std::uint8_t byte) { return byte == 0; });
}

class HardCaseTest : public ::testing::TestWithParam<NamedCase> {};

}  // namespace

// Each variant's frame through the measurement session, which compares it
// with the unculled frame and, where they differ, with the unculled frame
// drawn in the variant's own order, in which a culled leaf changes a pixel
// only where it is strictly in front (evaluation/lost_pixels.h): culling
// changes which nodes share a batch, and so the order leaves are drawn in,
// and where faces tie in depth the leaf drawn first keeps the pixel
// (measured: om-mos and pc-mos on the coplanar faces, every visible leaf
// drawn, 1,014 tied pixels different). No variant may lose a pixel.
TEST_P(HardCaseTest, EveryConservativeStrategyDrawsTheUnculledFrame)
{
    const HardCase c = GetParam().make();
    gl::OffscreenContext ctx(c.width, c.height);
    const SceneSetup setup(c.scene, c.hierarchy, GetParam().name);
    // Per process and case: meson runs this binary once per driver, at the same time.
    DatabaseProvider databases(::testing::TempDir() + "occu-hard-case-" + GetParam().name + "-" +
                                   std::to_string(getpid()),
                               DatabaseProvider::Makes::required, nullptr);
    MeasurementSession session(setup, ctx, integration::checking_session_options(&databases));
    for (const StrategyTestVariant &v : hard_case_variants(c.width)) {
        const StrategyChoice choice = choose_strategy(v.spec, small_databases);
        if (const std::string why = choice.family->refusal(c.scene); !why.empty()) {
            EXPECT_THROW(integration::add_variant(session, v, small_databases), std::invalid_argument)
                << v.spec << " must refuse: " << why;
            continue;
        }
        integration::add_variant(session, v, small_databases);
    }

    // The premise and what the oracle sees, checked on the session's frame
    // before its first strategy's result is judged.
    bool premise_checked = false;
    const std::size_t bytes = std::size_t(c.width) * std::size_t(c.height) * 4;
    session.measure(0, c.camera, [&](const SessionStrategy &s, const StrategyFrame &f) {
        if (!premise_checked) {
            premise_checked = true;
            if (c.premise) {
                EXPECT_TRUE(c.premise(setup.hierarchy(), *f.frame)) << "the case is not the one it is named for";
            }
            if (c.hides_leaves) {
                EXPECT_FALSE(f.frame->truth->visible.empty()) << "the oracle sees nothing";
                EXPECT_LT(f.frame->truth->visible.size(), f.frame->truth->in_frustum.size())
                    << "nothing in the frustum is hidden";
            }
        }
        if (s.strategy.choice.name == "none") {
            EXPECT_EQ(all_background(ctx.pixels(), bytes), c.empty_frame)
                << (c.empty_frame ? "the unculled frame shows something" : "the unculled frame is empty");
        }
        EXPECT_EQ(f.loss.lost, 0u) << s.label << " lost pixels; visible leaves it did not draw:"
                                   << integration::visible_leaves_not_drawn(f);
    });
    EXPECT_TRUE(premise_checked) << "no strategy drew the case";
    std::filesystem::remove_all(databases.directory());
}

INSTANTIATE_TEST_SUITE_P(HardCases, HardCaseTest, ::testing::ValuesIn(hard_cases),
                         [](const ::testing::TestParamInfo<NamedCase> &info) { return std::string(info.param.name); });
