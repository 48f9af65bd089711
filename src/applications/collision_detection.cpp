// SPDX-License-Identifier: MIT
#include "applications/collision_detection.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "gl/state.h"

namespace occu {

namespace {

// A convex polygon being clipped: a triangle gains at most one vertex per
// plane (a convex polygon crosses a plane at most twice), so 3 + 10 planes
// fit.
struct Polygon {
    std::array<glm::dvec3, 16> v;
    int n = 0;
};

double side(const glm::dvec4 &plane, const glm::dvec3 &p)
{
    return glm::dot(glm::dvec3(plane), p) + plane.w;
}

// Sutherland and Hodgman's step: the part of `poly` in the closed half-space
// of `plane` (points on the plane are kept, so touching counts).
void clip(Polygon &poly, const glm::dvec4 &plane)
{
    Polygon out;
    for (int i = 0; i < poly.n; ++i) {
        const glm::dvec3 &a = poly.v[std::size_t(i)], &b = poly.v[std::size_t((i + 1) % poly.n)];
        const double da = side(plane, a), db = side(plane, b);
        if (da >= 0.0 && out.n < int(out.v.size()))
            out.v[std::size_t(out.n++)] = a;
        if ((da >= 0.0) != (db >= 0.0) && out.n < int(out.v.size()))
            out.v[std::size_t(out.n++)] = a + (da / (da - db)) * (b - a);
    }
    poly = out;
}

glm::dvec4 normalized(const glm::dvec4 &p)
{
    return p / glm::length(glm::dvec3(p));
}

glm::dvec4 row(const glm::dmat4 &m, int i)
{
    return {m[0][i], m[1][i], m[2][i], m[3][i]};
}

// The box is outside the plane when its corner farthest along the normal is.
bool box_outside(const Aabb &box, const glm::dvec4 &plane)
{
    const glm::dvec3 far_corner{plane.x >= 0 ? box.max.x : box.min.x, plane.y >= 0 ? box.max.y : box.min.y,
                                plane.z >= 0 ? box.max.z : box.min.z};
    return side(plane, far_corner) < 0.0;
}

}  // namespace

const char *heading_name(int tile)
{
    // Figure 7, row by row.
    static const char *const names[collision_tile_count] = {
        "straight-up-left",   "straight-up",   "straight-up-right",     //
        "straight-left",      "straight",      "straight-right",        //
        "straight-down-left", "straight-down", "straight-down-right"};
    return tile >= 0 && tile < collision_tile_count ? names[tile] : "?";
}

std::array<PixelRect, collision_tile_count> heading_tiles(const PixelRect &viewport)
{
    const int w = viewport.width(), h = viewport.height();
    // round(k n / 3) for k = 0..3, in integers.
    auto edge = [](int k, int n) { return (2 * k * n + 3) / 6; };
    std::array<PixelRect, collision_tile_count> tiles;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            // Row 0 is the figure's top row: the highest window y.
            const int y_row = 2 - r;
            tiles[std::size_t(3 * r + c)] = {viewport.x0 + edge(c, w), viewport.y0 + edge(y_row, h),
                                             viewport.x0 + edge(c + 1, w), viewport.y0 + edge(y_row + 1, h)};
        }
    return tiles;
}

const char *step_direction_name(StepDirection direction)
{
    return direction == StepDirection::forward ? "forward" : "backward";
}

Camera check_camera(const Camera &camera, StepDirection direction)
{
    if (direction == StepDirection::forward)
        return camera;
    Camera turned = camera;
    turned.target = camera.position - (camera.target - camera.position);
    return turned;
}

StepVolume::StepVolume(const Camera &camera, double step_length, StepDirection direction, int width, int height,
                       double margin)
    : camera_(check_camera(camera, direction)), width_(width), height_(height)
{
    if (width < 3 || height < 3)
        throw std::invalid_argument("a collision check needs a viewport of at least 3x3 pixels (one per tile), got " +
                                    std::to_string(width) + "x" + std::to_string(height));
    if (!std::isfinite(step_length) || !(step_length > double(camera.near_plane)) ||
        !(step_length < double(camera.far_plane))) {
        char why[200];
        std::snprintf(why, sizeof(why),
                      "a step of %g m has no check volume: it must reach beyond the near plane (%g m) and stay "
                      "before the far plane (%g m)",
                      step_length, double(camera.near_plane), double(camera.far_plane));
        throw std::invalid_argument(why);
    }
    // The near plane moves nearer by the margin, but never onto the eye.
    near_ = std::max(double(camera.near_plane) - margin, 1e-3 * double(camera.near_plane));
    far_ = step_length + margin;
    // The matrices the GL gets: the camera's float ones, read in double.
    view_ = glm::dmat4(camera_.view());
    projection_ = glm::dmat4(camera_.projection());
    const glm::dmat4 m = projection_ * view_;
    const glm::dvec4 x = row(m, 0), y = row(m, 1), w = row(m, 3), depth = -row(view_, 2);
    // Clip w is the view depth (> 0 inside the volume), so NDC x >= a is
    // the half-space x - a w >= 0, and so on.
    auto x_at_least = [&](double a) { return normalized(x - a * w); };
    auto x_at_most = [&](double b) { return normalized(b * w - x); };
    auto y_at_least = [&](double a) { return normalized(y - a * w); };
    auto y_at_most = [&](double b) { return normalized(b * w - y); };
    planes_ = {normalized(depth - glm::dvec4(0, 0, 0, near_)), normalized(glm::dvec4(0, 0, 0, far_) - depth),
               x_at_least(-1.0), x_at_most(1.0), y_at_least(-1.0), y_at_most(1.0)};
    // Tile edges in normalized device coordinates, from their pixel edges.
    const auto tiles = heading_tiles({0, 0, width, height});
    for (int k = 0; k < collision_tile_count; ++k) {
        const PixelRect &t = tiles[std::size_t(k)];
        tile_planes_[std::size_t(k)] = {x_at_least(2.0 * t.x0 / width - 1.0), x_at_most(2.0 * t.x1 / width - 1.0),
                                        y_at_least(2.0 * t.y0 / height - 1.0), y_at_most(2.0 * t.y1 / height - 1.0)};
    }
}

double StepVolume::far_ndc_z() const
{
    const glm::dvec4 c = projection_ * glm::dvec4(0.0, 0.0, -far_, 1.0);
    return c.z / c.w;
}

std::vector<std::uint32_t> leaves_within_reach(const Hierarchy &hierarchy, const StepVolume &volume)
{
    std::vector<std::uint32_t> leaves;
    const auto &nodes = hierarchy.nodes();
    if (nodes.empty())
        return leaves;
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty()) {
        const std::uint32_t n = stack.back();
        stack.pop_back();
        const HierarchyNode &node = nodes[n];
        if (node.bounds.empty() ||
            std::any_of(volume.planes().begin(), volume.planes().end(),
                        [&](const glm::dvec4 &p) { return box_outside(node.bounds, p); }))
            continue;
        if (node.leaf())
            leaves.push_back(n);
        for (std::uint32_t c = 0; c < node.child_count; ++c)
            stack.push_back(node.first_child + c);
    }
    std::sort(leaves.begin(), leaves.end());
    return leaves;
}

// The tolerance. Window depth of view depth z (depth range [0, 1], the
// camera's perspective with near n and far f) is w(z) = f (z - n) / ((f - n) z),
// so dw/dz = f n / ((f - n) z^2): an error dw in window depth at the far
// plane z = s is an error dw (f - n) s^2 / (f n) in view depth. The errors
// between the far face's fragment and the scene's stored depth there:
//  (a) both are rounded to the 24-bit depth buffer: a quantum 2^-24 each;
//  (b) the scene's depth is interpolated in float over its triangle, a
//      plane equation z0 + x dz/dx + y dz/dy whose terms can exceed w:
//      a few ulps of numbers below 1, 2^-24 each;
//      (a) and (b) together: 16 quanta, with room to spare;
//  (c) the scene's vertices go through float matrices: coordinates of
//      magnitude up to |eye| + s (anything within the step) carry a
//      rounding of 2^-24 of that per operation, a handful of operations
//      (the view matrix's translation holds the eye's rounding, the 4x4
//      product sums four terms): 8 (|eye| + s) 2^-24 metres of view depth,
//      at the far plane and at the near plane alike.
// The projection's own rounding (its entries are floats) is shared by the
// far face and the scene, so it does not separate them.
double step_depth_tolerance(const Camera &camera, double step_length)
{
    const double quantum = std::ldexp(1.0, -24);
    const double n = camera.near_plane, f = camera.far_plane, s = step_length;
    const double depth_buffer = 16.0 * quantum * (f - n) * s * s / (f * n);
    const double transforms = 8.0 * quantum * (glm::length(glm::dvec3(camera.position)) + s);
    return depth_buffer + transforms;
}

bool CollisionResult::any() const
{
    return std::any_of(tiles.begin(), tiles.end(), [](const TileCheck &t) { return t.collides; });
}

void draw_collision_frame(const SceneRenderer &renderer, const Hierarchy &hierarchy, const Camera &camera)
{
    // Back faces stay: a wall seen from behind, or the inside of a building
    // the eye is in, stops a walker as a front face does.
    const gl::AttribScope state(GL_ENABLE_BIT | GL_DEPTH_BUFFER_BIT | GL_POLYGON_BIT);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl::load_camera(camera);
    for (std::uint32_t leaf : leaves_in_frustum(hierarchy, Frustum(camera.view_projection())))
        renderer.draw_leaf(leaf, LeafPart::all);   // see-through surfaces stop a walker too
}

CollisionCheck::CollisionCheck(const SceneRenderer &renderer, const Hierarchy &hierarchy)
    : renderer_(renderer), hierarchy_(hierarchy)
{
    if (unit_.max_tiles() < collision_tile_count)
        throw std::runtime_error("the occlusion unit has " + std::to_string(unit_.max_tiles()) +
                                 " tiles, collision checks need 9");
}

CollisionResult CollisionCheck::check(const Camera &camera, float step_length, StepDirection direction)
{
    // No image of the scene behind the user is in the framebuffer: the
    // paper's second pass.
    if (direction == StepDirection::backward)
        return check_own_pass(camera, step_length, direction);
    GLint viewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_VIEWPORT, viewport);
    const StepVolume volume(camera, step_length, direction, viewport[2], viewport[3]);
    return test_far_face(volume, {viewport[0], viewport[1], viewport[0] + viewport[2], viewport[1] + viewport[3]});
}

CollisionResult CollisionCheck::check_own_pass(const Camera &camera, float step_length, StepDirection direction)
{
    GLint viewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_VIEWPORT, viewport);
    const StepVolume volume(camera, step_length, direction, viewport[2], viewport[3]);
    // Only what can reach into the volume (see the header): the counts are
    // those of the whole view.
    const std::vector<std::uint32_t> leaves = leaves_within_reach(hierarchy_, volume);
    last_pass_leaves_ = leaves.size();
    if (!target_)
        target_.emplace(volume.width(), volume.height());
    target_->resize(volume.width(), volume.height());
    const gl::Framebuffer::Bind bind(*target_);
    {
        const gl::AttribScope state(GL_ENABLE_BIT | GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_POLYGON_BIT);
        const gl::MatrixScope matrices;
        glDisable(GL_CULL_FACE);   // back faces are walls too
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_POLYGON_OFFSET_FILL);
        glDisable(GL_ALPHA_TEST);
        glDisable(GL_DEPTH_CLAMP);   // what lies in front of the near plane is clipped, as in the frame
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);   // depth is all the check reads
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        gl::load_camera(volume.camera());
        for (std::uint32_t leaf : leaves)
            renderer_.draw_leaf_flat(leaf, LeafPart::all);
    }
    return test_far_face(volume, {0, 0, volume.width(), volume.height()});
}

CollisionResult CollisionCheck::test_far_face(const StepVolume &volume, const PixelRect &viewport)
{
    const auto tiles = heading_tiles(viewport);
    const double z = volume.far_ndc_z();
    CollisionResult result;
    const gl::AttribScope state(GL_ENABLE_BIT | GL_DEPTH_BUFFER_BIT | GL_POLYGON_BIT);
    const gl::MatrixScope matrices;
    // "backface culling must be disabled, in order to detect intersections
    // with the backfacing polygons of the view-frustum" (section 5).
    glDisable(GL_CULL_FACE);
    // Nothing but the depth test may decide a fragment.
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_ALPHA_TEST);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    // The far face in normalized device coordinates: one quad over the
    // viewport at the far plane's depth, exactly the depth the camera's
    // projection gives a point at view depth step_length (only this face
    // of the volume can fail a depth test; see the header).
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    gl::OcclusionPass pass(unit_, gl::OcclusionMode::brief, std::vector<PixelRect>(tiles.begin(), tiles.end()));
    glBegin(GL_QUADS);
    glVertex3d(-1.0, -1.0, z);
    glVertex3d(1.0, -1.0, z);
    glVertex3d(1.0, 1.0, z);
    glVertex3d(-1.0, 1.0, z);
    glEnd();
    const std::vector<gl::OcclusionRecord> &records = pass.end();
    for (int k = 0; k < collision_tile_count; ++k) {
        TileCheck &t = result.tiles[std::size_t(k)];
        t.nohc = records[std::size_t(k)].nohc;
        t.phc = records[std::size_t(k)].phc;
        // "If the number of non-occlusion hits is different from the number
        // of projection hits, [...] a collision can be expected."
        t.collides = t.nohc != t.phc;
    }
    return result;
}

const char *agreement_name(Agreement a)
{
    switch (a) {
    case Agreement::agree: return "agree";
    case Agreement::sub_pixel: return "sub-pixel";
    case Agreement::depth_precision: return "depth-precision";
    case Agreement::unexplained: return "unexplained";
    }
    return "?";
}

ExactCollisionTest::ExactCollisionTest(const Scene &scene, const Hierarchy &hierarchy)
    : scene_(scene), hierarchy_(hierarchy)
{
}

template <class Visit>
void ExactCollisionTest::for_each_triangle(const StepVolume &volume, Visit &&visit) const
{
    for (std::uint32_t leaf : leaves_within_reach(hierarchy_, volume)) {
        const HierarchyNode &node = hierarchy_.nodes()[leaf];
        for (std::uint32_t t = 0; t < node.triangle_count; ++t) {
            const TriangleRef &ref = hierarchy_.triangles()[node.first_triangle + t];
            const Mesh &mesh = scene_.meshes[ref.mesh];
            const std::uint32_t *v = &mesh.indices[ref.first_index];
            const glm::dvec3 a(mesh.positions[v[0]]), b(mesh.positions[v[1]]), c(mesh.positions[v[2]]);
            if (!visit(a, b, c))
                return;
        }
    }
}

std::array<bool, collision_tile_count> ExactCollisionTest::check(const Camera &camera, float step_length,
                                                                 StepDirection direction, int width, int height) const
{
    return check(StepVolume(camera, step_length, direction, width, height));
}

std::array<bool, collision_tile_count> ExactCollisionTest::check(const StepVolume &volume) const
{
    std::array<bool, collision_tile_count> hit{};
    int hits = 0;
    for_each_triangle(volume, [&](const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c) {
        // The triangle's part inside the whole volume, then inside each
        // tile's sub-frustum (the same near and far planes, the tile's sides).
        Polygon inside;
        inside.v[0] = a;
        inside.v[1] = b;
        inside.v[2] = c;
        inside.n = 3;
        for (const glm::dvec4 &p : volume.planes()) {
            clip(inside, p);
            if (inside.n == 0)
                return true;
        }
        for (int k = 0; k < collision_tile_count; ++k) {
            if (hit[std::size_t(k)])
                continue;
            Polygon part = inside;
            for (const glm::dvec4 &p : volume.tile_planes(k))
                clip(part, p);
            if (part.n > 0) {
                hit[std::size_t(k)] = true;
                ++hits;
            }
        }
        return hits < collision_tile_count;   // all tiles hit: nothing left to find
    });
    return hit;
}

std::array<Agreement, collision_tile_count> ExactCollisionTest::explain(
    const Camera &camera, float step_length, StepDirection direction, int width, int height,
    const CollisionResult &gl, const std::array<bool, collision_tile_count> &exact) const
{
    std::array<Agreement, collision_tile_count> why;
    why.fill(Agreement::agree);
    bool any = false;
    for (int k = 0; k < collision_tile_count; ++k)
        any |= gl.tiles[std::size_t(k)].collides != exact[std::size_t(k)];
    if (!any)
        return why;
    const double tolerance = step_depth_tolerance(camera, step_length);
    const StepVolume volume(camera, step_length, direction, width, height);
    const StepVolume grown(camera, step_length, direction, width, height, tolerance);
    const std::array<bool, collision_tile_count> grown_hit = check(grown);
    const double n = volume.near_depth(), s = volume.far_depth();
    const glm::dmat4 m = volume.projection() * volume.view(), inverse = glm::inverse(m);
    const glm::dvec3 eye = glm::dvec3(glm::inverse(volume.view())[3]);
    const glm::dvec4 depth_row = -row(volume.view(), 2);
    const auto tiles = heading_tiles({0, 0, width, height});
    for (int k = 0; k < collision_tile_count; ++k) {
        const bool g = gl.tiles[std::size_t(k)].collides, e = exact[std::size_t(k)];
        if (g == e)
            continue;
        if (g) {
            // The GL found geometry nearer than the far face where none is
            // inside the volume: only depth precision can put it there.
            why[std::size_t(k)] = grown_hit[std::size_t(k)] ? Agreement::depth_precision : Agreement::unexplained;
            continue;
        }
        // The exact test found geometry the GL did not: cast the tile's
        // pixel-centre rays through the triangles that meet the grown tile
        // volume. A hit clearly inside [n, s] is a pixel the GL should have
        // counted (unexplained); hits only within the tolerance of either
        // plane are depth precision; no hit at all, sub-pixel geometry.
        const PixelRect &tile = tiles[std::size_t(k)];
        bool core = false, band = false;
        for_each_triangle(grown, [&](const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c) {
            Polygon part;
            part.v[0] = a;
            part.v[1] = b;
            part.v[2] = c;
            part.n = 3;
            for (const glm::dvec4 &p : grown.planes())
                clip(part, p);
            for (const glm::dvec4 &p : grown.tile_planes(k))
                clip(part, p);
            if (part.n == 0)
                return true;
            // The window-space box of the part: the pixel centres it can cover.
            double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
            for (int i = 0; i < part.n; ++i) {
                const glm::dvec4 q = m * glm::dvec4(part.v[std::size_t(i)], 1.0);
                const double wx = (0.5 * q.x / q.w + 0.5) * width, wy = (0.5 * q.y / q.w + 0.5) * height;
                x0 = std::min(x0, wx), x1 = std::max(x1, wx), y0 = std::min(y0, wy), y1 = std::max(y1, wy);
            }
            const int px0 = std::max(tile.x0, int(std::ceil(x0 - 0.5)));
            const int px1 = std::min(tile.x1 - 1, int(std::floor(x1 - 0.5)));
            const int py0 = std::max(tile.y0, int(std::ceil(y0 - 0.5)));
            const int py1 = std::min(tile.y1 - 1, int(std::floor(y1 - 0.5)));
            const glm::dvec3 e1 = b - a, e2 = c - a;
            for (int py = py0; py <= py1 && !core; ++py)
                for (int px = px0; px <= px1 && !core; ++px) {
                    // The ray from the eye through the pixel centre, by the
                    // centre's point on the near plane.
                    const glm::dvec4 h = inverse * glm::dvec4(2.0 * (px + 0.5) / width - 1.0,
                                                              2.0 * (py + 0.5) / height - 1.0, -1.0, 1.0);
                    const glm::dvec3 dir = glm::dvec3(h) / h.w - eye;
                    // Moeller and Trumbore's ray-triangle test, both sides.
                    const glm::dvec3 pv = glm::cross(dir, e2);
                    const double det = glm::dot(e1, pv);
                    if (det == 0.0)
                        continue;   // edge-on: the GL draws no fragment either
                    const glm::dvec3 tv = eye - a;
                    const double u = glm::dot(tv, pv) / det;
                    if (u < 0.0 || u > 1.0)
                        continue;
                    const glm::dvec3 qv = glm::cross(tv, e1);
                    const double v = glm::dot(dir, qv) / det;
                    if (v < 0.0 || u + v > 1.0)
                        continue;
                    const double t = glm::dot(e2, qv) / det;
                    if (t <= 0.0)
                        continue;
                    const double depth = glm::dot(glm::dvec3(depth_row), eye + t * dir) + depth_row.w;
                    if (depth >= n + tolerance && depth <= s - tolerance)
                        core = true;
                    else if (depth >= n - tolerance && depth <= s + tolerance)
                        band = true;
                }
            return !core;
        });
        why[std::size_t(k)] = core ? Agreement::unexplained : band ? Agreement::depth_precision : Agreement::sub_pixel;
    }
    return why;
}

}  // namespace occu
