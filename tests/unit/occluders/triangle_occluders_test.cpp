// SPDX-License-Identifier: MIT
// The scene's own triangles as occluders (occluders/triangle_occluders.h):
// against a brute-force ray cast, no box with a point the eye sees past
// every front-facing occluder triangle (the part of it beyond the near
// plane, as GL draws it) through some pixel centre ever reads occluded, on hand-made scenes: a thin
// wall with no volume for skins, a triangle across the near plane, a wall
// seen from behind, a see-through wall, and a heap of random triangles.
// And the thin wall does hide what stands behind it, which skins alone do not.
// Which triangles a frame takes is the budget's largest by score, as a
// scan of every triangle in double finds them.
#include "occluders/depth_occluders.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <vector>

#include "occluders/sources.h"
#include "scene/city.h"
#include "spatial/hierarchy.h"

using namespace occu;

namespace {

std::vector<SettingSpec> specs()
{
    std::vector<SettingSpec> s = skin_settings();
    s.push_back(occluder_triangles_setting());
    s.push_back(coverage_setting());
    return s;
}

void add_triangle(Mesh &m, glm::vec3 a, glm::vec3 b, glm::vec3 c)
{
    const auto first = std::uint32_t(m.positions.size());
    for (const glm::vec3 &p : {a, b, c}) {
        m.positions.push_back(p);
        m.normals.push_back(glm::vec3(0, 1, 0));
    }
    m.indices.insert(m.indices.end(), {first, first + 1, first + 2});
}

// A quad a, b, c, d counter-clockwise seen from its front.
void add_quad(Mesh &m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d)
{
    add_triangle(m, a, b, c);
    add_triangle(m, a, c, d);
}

// The distance along the ray from `eye` in direction `dir` to the nearest
// front-facing occluder triangle it meets beyond the near plane (its view
// depth along `forward` past `near`), as GL's depth test sees it; infinity
// when none (Moeller-Trumbore, in double).
double nearest_occluder(const Scene &scene, glm::dvec3 eye, glm::dvec3 dir, glm::dvec3 forward, double near)
{
    double nearest = std::numeric_limits<double>::infinity();
    for (const Mesh &m : scene.meshes) {
        if (!m.occluder)
            continue;
        for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
            const glm::dvec3 a(m.positions[m.indices[i]]), b(m.positions[m.indices[i + 1]]),
                c(m.positions[m.indices[i + 2]]);
            const glm::dvec3 e1 = b - a, e2 = c - a;
            if (glm::dot(glm::cross(e1, e2), eye - a) <= 0.0)
                continue;   // a back face: GL culls it
            const glm::dvec3 h = glm::cross(dir, e2);
            const double det = glm::dot(e1, h);
            if (std::abs(det) < 1e-12)
                continue;
            const glm::dvec3 s = eye - a;
            const double u = glm::dot(s, h) / det;
            const glm::dvec3 q = glm::cross(s, e1);
            const double v = glm::dot(dir, q) / det;
            const double t = glm::dot(e2, q) / det;
            if (u < 0 || v < 0 || u + v > 1 || t <= 0)
                continue;
            if (glm::dot(dir * t, forward) > near)
                nearest = std::min(nearest, t);
        }
    }
    return nearest;
}

// Whether GL would show some of `box` (drawn with its faces, beyond the
// near plane) at some pixel centre of the frame: the ray through the
// centre enters the box before it meets any occluder, by a margin for
// depth rounding.
bool seen(const Scene &scene, const Camera &camera, const Frame &frame, const Aabb &box)
{
    const glm::dvec3 eye(camera.position);
    const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - eye);
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(frame.view_projection));
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            const glm::dvec4 ndc((x + 0.5) / frame.width * 2.0 - 1.0, (y + 0.5) / frame.height * 2.0 - 1.0, 1.0, 1.0);
            const glm::dvec4 far = inverse * ndc;
            const glm::dvec3 dir = glm::dvec3(far) / far.w - eye;
            // The ray's entry into the box (slabs).
            double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
            for (int k = 0; k < 3; ++k) {
                if (std::abs(dir[k]) < 1e-15) {
                    if (eye[k] < box.min[k] || eye[k] > box.max[k])
                        t1 = -1.0;
                    continue;
                }
                double a = (double(box.min[k]) - eye[k]) / dir[k], b = (double(box.max[k]) - eye[k]) / dir[k];
                if (a > b)
                    std::swap(a, b);
                t0 = std::max(t0, a);
                t1 = std::min(t1, b);
            }
            if (t0 > t1 || glm::dot(dir * t0, forward) <= double(camera.near_plane))
                continue;
            if (t0 < nearest_occluder(scene, eye, dir, forward, double(camera.near_plane)) * (1.0 + 1e-6))
                return true;
        }
    return false;
}

struct Counts {
    int occluded = 0, seen_occluded = 0;
};

// Every box of `boxes` tested as the skins culler tests a leaf.
// With merged coverage (coverage=merged) as that setting asks.
Counts check(const Scene &scene, const Camera &camera, const std::vector<Aabb> &boxes, long budget,
             bool merged = false)
{
    const std::vector<SettingSpec> s = specs();
    Settings settings("test", &s);
    settings.set("occluder-triangles", std::to_string(budget));
    settings.set("coverage", merged ? "merged" : "whole");
    DepthOccluders occluders(scene, settings);
    const int size = 96;
    const Frame frame(camera, size, size);
    Counts counts;
    for (int divisor : {1, 2}) {
        DepthRasterizer raster;
        raster.begin(frame.view_projection, size, size,
                     {divisor, true, merges_partial_coverage(settings, divisor)});
        occluders.render(frame, raster, 0);
        for (const Aabb &box : boxes) {
            const auto f = frame.footprint(box);
            if (!f || f->rect.empty())
                continue;
            const float z = f->window_z_near - 1e-6f;
            if (!raster.occluded(box, f->rect, z))
                continue;
            ++counts.occluded;
            if (seen(scene, camera, frame, box)) {
                ++counts.seen_occluded;
                ADD_FAILURE() << "box (" << box.min.x << ", " << box.min.y << ", " << box.min.z << ")-(" << box.max.x
                              << ", " << box.max.y << ", " << box.max.z << ") is seen but read occluded, divisor "
                              << divisor << ", budget " << budget;
            }
        }
    }
    return counts;
}

std::vector<Aabb> grid_of_boxes(glm::vec3 lo, glm::vec3 hi, int n, float size)
{
    std::vector<Aabb> boxes;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                const glm::vec3 t(float(i) / float(n - 1), float(j) / float(n - 1), float(k) / float(n - 1));
                const glm::vec3 c = lo + (hi - lo) * t;
                boxes.push_back(Aabb::of(c - glm::vec3(size), c + glm::vec3(size)));
            }
    return boxes;
}

Camera looking_down_minus_z()
{
    Camera c;
    c.position = {0, 2, 0};
    c.target = {0, 2, -1};
    c.near_plane = 0.5f;
    return c;
}

Scene one_mesh(Mesh m, bool occluder = true)
{
    Scene scene;
    m.occluder = occluder;
    m.update_bounds();
    scene.meshes.push_back(std::move(m));
    scene.update_bounds();
    return scene;
}

}  // namespace

TEST(TriangleOccluders, AThinWallHidesWhatIsBehindItAndNothingSeen)
{
    Mesh wall;   // 10 m x 5 m, no thickness, facing the eye (+z)
    add_quad(wall, {-5, 0, -10}, {5, 0, -10}, {5, 5, -10}, {-5, 5, -10});
    const Scene scene = one_mesh(wall);
    const auto boxes = grid_of_boxes({-12, -1, -40}, {12, 6, -11}, 7, 0.4f);
    const Counts without = check(scene, looking_down_minus_z(), boxes, 0);
    EXPECT_EQ(without.occluded, 0) << "skins find no volume in a wall of no thickness";
    const Counts with = check(scene, looking_down_minus_z(), boxes, 64);
    EXPECT_GT(with.occluded, 20) << "the wall's own triangles hide the boxes behind it";
    EXPECT_EQ(with.seen_occluded, 0);
}

TEST(TriangleOccluders, ATriangleAcrossTheNearPlaneHidesOnlyWhatItsDrawnPartHides)
{
    Mesh m;   // from 3 m behind the eye to 25 m ahead, slanting across the view
    add_triangle(m, {-1, -6, 3}, {6, 3, -25}, {-1, 12, 3});
    glm::vec3 e1 = m.positions[1] - m.positions[0], e2 = m.positions[2] - m.positions[0];
    if (glm::dot(glm::cross(e1, e2), looking_down_minus_z().position - m.positions[0]) < 0)
        std::swap(m.indices[1], m.indices[2]);
    const Scene scene = one_mesh(m);
    const auto boxes = grid_of_boxes({-4, -3, -30}, {12, 8, -2}, 8, 0.3f);
    for (float near : {0.1f, 0.5f, 2.0f}) {
        Camera c = looking_down_minus_z();
        c.near_plane = near;
        const Counts counts = check(scene, c, boxes, 4);
        EXPECT_GT(counts.occluded, 0) << "near " << near << ": the part beyond the near plane hides something";
        EXPECT_EQ(counts.seen_occluded, 0) << "near " << near;
    }
}

TEST(TriangleOccluders, AWallSeenFromBehindOrSeeThroughHidesNothing)
{
    Mesh back;   // facing away from the eye: GL culls it
    add_quad(back, {-5, 0, -10}, {-5, 5, -10}, {5, 5, -10}, {5, 0, -10});
    const auto boxes = grid_of_boxes({-4, 0, -30}, {4, 5, -11}, 5, 0.4f);
    EXPECT_EQ(check(one_mesh(back), looking_down_minus_z(), boxes, 64).occluded, 0);
    Mesh glass;
    add_quad(glass, {-5, 0, -10}, {5, 0, -10}, {5, 5, -10}, {-5, 5, -10});
    EXPECT_EQ(check(one_mesh(glass, false), looking_down_minus_z(), boxes, 64).occluded, 0)
        << "a see-through mesh (Mesh::occluder false) is never an occluder";
}

TEST(TriangleOccluders, RandomTrianglesNeverHideASeenBox)
{
    std::mt19937 rng(29);
    std::uniform_real_distribution<float> x(-8, 8), y(-2, 6), z(-30, -1), d(-3, 3);
    Mesh m;
    for (int i = 0; i < 40; ++i) {
        const glm::vec3 a(x(rng), y(rng), z(rng));
        add_triangle(m, a, a + glm::vec3(d(rng), d(rng), d(rng)), a + glm::vec3(d(rng), d(rng), d(rng)));
    }
    const Scene scene = one_mesh(m);
    const auto boxes = grid_of_boxes({-8, -2, -32}, {8, 6, -3}, 7, 0.25f);
    int occluded = 0;
    for (int view = 0; view < 4; ++view) {
        Camera c = looking_down_minus_z();
        c.position.x = float(view) - 1.5f;
        c.target = c.position + glm::vec3(0.1f * float(view - 2), 0.0f, -1.0f);
        for (long budget : {8L, 1000L}) {
            const Counts counts = check(scene, c, boxes, budget);
            occluded += counts.occluded;
            EXPECT_EQ(counts.seen_occluded, 0) << "view " << view;
        }
    }
    EXPECT_GT(occluded, 0) << "some box is hidden by the heap";
}

// A wall of many small triangles sharing their vertices, gently rumpled,
// as a level's patches and a building's tessellated walls are: whole depth
// pixels leave a seam along every shared edge, so it hides little; merged
// coverage fuses the triangles (and the samples along their shared edges)
// and hides what stands behind it, never a box the eye sees.
TEST(TriangleOccluders, ATessellatedWallHidesWithMergedCoverageWhatItsSeamsHideNot)
{
    Mesh wall;
    const int columns = 24, rows = 12;
    for (int j = 0; j <= rows; ++j)
        for (int i = 0; i <= columns; ++i) {
            const float bump = 0.05f * float((i * 7 + j * 3) % 5) - 0.1f;
            wall.positions.push_back({-6.0f + 12.0f * float(i) / columns, -1.0f + 7.0f * float(j) / rows, -10.0f + bump});
            wall.normals.push_back({0, 0, 1});
        }
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            const auto at = [&](int x, int y) { return std::uint32_t(y * (columns + 1) + x); };
            wall.indices.insert(wall.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            wall.indices.insert(wall.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    const Scene scene = one_mesh(wall);
    const auto boxes = grid_of_boxes({-5, 0, -30}, {5, 5, -12}, 7, 0.6f);
    const Counts whole = check(scene, looking_down_minus_z(), boxes, 100000);
    const Counts merged = check(scene, looking_down_minus_z(), boxes, 100000, true);
    EXPECT_EQ(whole.seen_occluded, 0);
    EXPECT_EQ(merged.seen_occluded, 0);
    EXPECT_GT(merged.occluded, 2 * whole.occluded + 20) << "whole pixels hide " << whole.occluded;
}

// At the families' defaults (scene-triangles on, occluder-triangles 0) a
// scene none of whose meshes has a skin takes its own triangles, and one
// with a closed mesh its skins alone; scene-triangles=off leaves the
// first without occluders.
TEST(TriangleOccluders, AtTheDefaultsASceneWithoutSkinsTakesItsOwnTriangles)
{
    std::vector<SettingSpec> s = specs();
    s.push_back(scene_triangles_setting());
    const Camera camera = looking_down_minus_z();
    const Frame frame(camera, 96, 96);
    const auto drawn = [&](const Scene &scene, bool scene_triangles) {
        Settings settings("test", &s);
        settings.set("scene-triangles", scene_triangles ? "on" : "off");
        DepthOccluders occluders(scene, settings);
        DepthRasterizer raster;
        raster.begin(frame.view_projection, 96, 96, {2, true, false});
        return occluders.render(frame, raster, 0);
    };
    Mesh wall;   // open: no skin
    add_quad(wall, {-5, 0, -10}, {5, 0, -10}, {5, 5, -10}, {-5, 5, -10});
    const Scene open_scene = one_mesh(wall);
    EXPECT_EQ(drawn(open_scene, true), 2u) << "the wall's two triangles";
    EXPECT_EQ(drawn(open_scene, false), 0u);

    Mesh cube;   // closed, 4 m a side, its faces outward
    const glm::vec3 lo(-2, 0, -14), hi(2, 4, -10);
    for (const auto &face : aabb_faces) {
        glm::vec3 c[4];
        for (int i = 0; i < 4; ++i)
            c[i] = Aabb::of(lo, hi).corner(face[i]);
        add_quad(cube, c[0], c[1], c[2], c[3]);
    }
    const Scene closed_scene = one_mesh(cube);
    const SkinOccluders skins(closed_scene, "", 8);
    ASSERT_GT(skins.size(), 0u) << "the cube has a skin";
    EXPECT_EQ(drawn(closed_scene, true), drawn(closed_scene, false)) << "with skins, no triangle joins them";
}

TEST(TriangleOccluders, MergedCoverageRefusesADivisorAboveEight)
{
    const std::vector<SettingSpec> s = specs();
    Settings settings("hzb", &s);
    EXPECT_FALSE(merges_partial_coverage(settings, 64)) << "whole pixels, the default, take any divisor";
    settings.set("coverage", "merged");
    EXPECT_TRUE(merges_partial_coverage(settings, 8));
    try {
        merges_partial_coverage(settings, 9);
        ADD_FAILURE() << "map-divisor 9 accepted";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("coverage=merged"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("map-divisor 9"), std::string::npos) << e.what();
    }
    EXPECT_THROW(settings.set("coverage", "partial"), std::invalid_argument);
}

namespace {

// A triangle's score as TriangleOccluders documents it, in double: twice
// its projected area in normalized device coordinates where all its
// corners lie beyond the near plane, else twice its world area over its
// nearest corner's squared clip w (at least the near distance); nothing
// when it has no area, faces away or lies wholly outside one clip plane.
std::optional<double> brute_force_score(const Frame &frame, const std::array<glm::vec3, 3> &p)
{
    const glm::dmat4 vp(frame.view_projection);
    glm::dvec4 c[3];
    for (int v = 0; v < 3; ++v)
        c[v] = vp * glm::dvec4(glm::dvec3(p[v]), 1.0);
    for (int axis = 0; axis < 3; ++axis)
        if ((c[0][axis] > c[0].w && c[1][axis] > c[1].w && c[2][axis] > c[2].w) ||
            (c[0][axis] < -c[0].w && c[1][axis] < -c[1].w && c[2][axis] < -c[2].w))
            return std::nullopt;
    const double near = frame.camera.near_plane;
    if (c[0].w > near && c[1].w > near && c[2].w > near) {
        const glm::dvec2 a(c[0] / c[0].w), b(c[1] / c[1].w), d(c[2] / c[2].w);
        const double twice = (b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x);
        return twice > 0.0 ? std::optional<double>(twice) : std::nullopt;
    }
    const glm::dvec3 n = glm::cross(glm::dvec3(p[1] - p[0]), glm::dvec3(p[2] - p[0]));
    if (!(glm::dot(n, glm::dvec3(frame.camera.position) - glm::dvec3(p[0])) > 0.0))
        return std::nullopt;
    const double w = std::max(near, std::min({c[0].w, c[1].w, c[2].w}));
    return glm::length(n) > 0.0 ? std::optional<double>(glm::length(n) / (w * w)) : std::nullopt;
}

}  // namespace

// Random triangles of every size and slant around eyes with narrow and
// wide fields of view, some across the near plane, some beside or behind
// the eye: the leaves and triangles a frame skips cannot hold a triangle
// of the budget's best, so the chosen ones are the best by score (to a
// rounding of the score, for ties), drawn nearest first.
TEST(TriangleOccluders, TheChosenAreTheLargestByScore)
{
    std::mt19937 rng(41);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), exponent(-2.0f, 1.5f);
    Mesh m;
    for (int i = 0; i < 3000; ++i) {
        const glm::vec3 a(40.0f * unit(rng), 10.0f * unit(rng), 40.0f * unit(rng));
        const float size = std::pow(10.0f, exponent(rng));
        add_triangle(m, a, a + size * glm::vec3(unit(rng), unit(rng), unit(rng)),
                     a + size * glm::vec3(unit(rng), unit(rng), unit(rng)));
    }
    const Scene scene = one_mesh(m);
    HierarchyOptions leaves;
    leaves.max_leaf_triangles = 16;
    const Hierarchy hierarchy = Hierarchy::build(scene, leaves);
    const std::vector<SettingSpec> s = specs();
    int views = 0;
    for (const Hierarchy *h : {&hierarchy, static_cast<const Hierarchy *>(nullptr)})
        for (long budget : {20L, 300L}) {
            Settings settings("test", &s);
            settings.set("occluder-triangles", std::to_string(budget));
            TriangleOccluders occluders(scene, settings, 0, h);
            for (int view = 0; view < 12; ++view) {
                Camera camera;
                camera.position = glm::vec3(20.0f * unit(rng), 5.0f * unit(rng), 20.0f * unit(rng));
                camera.target = camera.position + glm::vec3(unit(rng), 0.3f * unit(rng), unit(rng));
                camera.fovy_degrees = std::array<float, 3>{50.0f, 90.0f, 130.0f}[view % 3];
                camera.aspect = view % 2 ? 1.6f : 1.0f;
                camera.near_plane = std::array<float, 2>{0.1f, 1.0f}[view / 3 % 2];
                const Frame frame(camera, 64, 64);
                // Each scene triangle's score, and the budget-th best.
                std::map<std::array<float, 9>, double> score;
                std::vector<double> scores;
                for (std::size_t i = 0; i < m.indices.size(); i += 3) {
                    const std::array<glm::vec3, 3> p{m.positions[m.indices[i]], m.positions[m.indices[i + 1]],
                                                     m.positions[m.indices[i + 2]]};
                    if (const auto sc = brute_force_score(frame, p)) {
                        score[{p[0].x, p[0].y, p[0].z, p[1].x, p[1].y, p[1].z, p[2].x, p[2].y, p[2].z}] = *sc;
                        scores.push_back(*sc);
                    }
                }
                std::sort(scores.begin(), scores.end(), std::greater<>());
                const std::size_t expected = std::min(std::size_t(budget), scores.size());
                ASSERT_GT(expected, 0u);
                const double cut = scores[expected - 1], tolerance = 1e-4;
                const std::vector<std::uint32_t> &chosen = occluders.choose(frame);
                ASSERT_EQ(chosen.size(), 3 * expected) << "view " << view << ", budget " << budget;
                const auto &corners = occluders.corners();
                double previous_nearest = -std::numeric_limits<double>::infinity();
                std::size_t above_cut = 0;
                for (std::size_t t = 0; t < chosen.size(); t += 3) {
                    const glm::vec3 &a = corners[chosen[t]], &b = corners[chosen[t + 1]], &c = corners[chosen[t + 2]];
                    const auto found = score.find({a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z});
                    ASSERT_NE(found, score.end()) << "view " << view << ": a chosen triangle scores nothing";
                    EXPECT_GE(found->second, cut * (1.0 - tolerance))
                        << "view " << view << ", budget " << budget << ": a triangle below the " << expected
                        << "th score chosen";
                    above_cut += found->second > cut * (1.0 + tolerance);
                    double nearest = std::numeric_limits<double>::infinity();
                    for (const glm::vec3 *q : {&a, &b, &c})
                        nearest = std::min(nearest, (glm::dmat4(frame.view_projection) * glm::dvec4(glm::dvec3(*q), 1.0)).w);
                    EXPECT_GE(nearest, previous_nearest - 1e-4) << "view " << view << ": not nearest first";
                    previous_nearest = nearest;
                }
                const auto all_above = std::size_t(std::count_if(scores.begin(), scores.end(), [&](double x) {
                    return x > cut * (1.0 + tolerance);
                }));
                EXPECT_EQ(above_cut, all_above) << "view " << view << ", budget " << budget
                                                << ": a triangle above the cut left out";
                ++views;
            }
        }
    EXPECT_EQ(views, 48);
}

// adapt-triangles' rule: five quarters of the triangles that reached past
// the buffer, rounded up, never below the least budget nor above the
// most; so it shrinks wherever fewer than four in five reach (but for the
// rounding up), grows wherever more do, and by a quarter a frame at most.
TEST(TriangleOccluders, AnAdaptedBudgetIsFiveQuartersOfThoseThatReachedWithinItsBounds)
{
    static_assert(TriangleOccluders::adapted_least == 64);
    EXPECT_EQ(TriangleOccluders::adapted_budget(0, 64, 1024), 64u);
    EXPECT_EQ(TriangleOccluders::adapted_budget(0, 128, 1024), 128u);
    EXPECT_EQ(TriangleOccluders::adapted_budget(100, 128, 1024), 128u);
    EXPECT_EQ(TriangleOccluders::adapted_budget(400, 128, 1024), 500u);
    EXPECT_EQ(TriangleOccluders::adapted_budget(401, 128, 1024), 502u);
    EXPECT_EQ(TriangleOccluders::adapted_budget(900, 128, 1024), 1024u);
    EXPECT_EQ(TriangleOccluders::adapted_budget(1024, 128, 1024), 1024u);
    EXPECT_EQ(TriangleOccluders::adapted_budget(1024, 1024, 1024), 1024u) << "a least budget as large as the most";
    EXPECT_EQ(TriangleOccluders::adapted_budget(3, 1024, 512), 1024u) << "the least wins";
    for (std::size_t budget = 128; budget <= 1024; budget += 7)
        for (std::size_t reached = 0; reached <= budget; ++reached) {
            const std::size_t next = TriangleOccluders::adapted_budget(reached, 128, 1024);
            ASSERT_GE(next, 128u);
            ASSERT_LE(next, 1024u);
            ASSERT_LE(next, std::max<std::size_t>(128, budget + (budget + 3) / 4)) << budget << ", " << reached;
            if (5 * reached + 4 <= 4 * budget && budget > 128) {
                ASSERT_LT(next, budget) << "shrinks where fewer than four in five reach, less one: " << budget << ", " << reached;
            }
            if (5 * reached > 4 * budget && budget < 1024) {
                ASSERT_GT(next, budget) << "grows where more than four in five reach: " << budget << ", " << reached;
            }
        }
}

// The budget a frame at a time: behind a near wall the triangles beyond it
// add nothing to the buffer and the budget shrinks to its least; turned
// to triangles nothing hides, it grows back to occluder-triangles.
// adapt-triangles=off, or scene-triangles' least budget as large as
// occluder-triangles, keeps the budget fixed.
TEST(TriangleOccluders, AdaptTrianglesShrinksBehindAWallAndGrowsWhereAllReach)
{
    Mesh m;
    // Looking down -z from the origin: a wall 2 m away across the whole
    // view, and 600 small triangles 20 m away behind it.
    add_quad(m, {-3, -3, -2}, {3, -3, -2}, {3, 3, -2}, {-3, 3, -2});
    // Looking down +z: 600 small triangles 10 m away, apart, nothing
    // before them. Facing the eye of their view each.
    for (int i = 0; i < 30; ++i)
        for (int j = 0; j < 20; ++j) {
            const float x = -6.0f + 0.4f * float(i), y = -4.0f + 0.4f * float(j);
            add_triangle(m, {x, y, -20}, {x + 0.25f, y, -20}, {x, y + 0.25f, -20});
            add_triangle(m, {x, y, 10}, {x, y + 0.25f, 10}, {x + 0.25f, y, 10});
        }
    const Scene scene = one_mesh(m);
    std::vector<SettingSpec> s = specs();
    s.push_back(adapt_triangles_setting());
    Camera behind_wall, open;
    behind_wall.position = open.position = {0, 0, 0};
    behind_wall.target = {0, 0, -1};
    open.target = {0, 0, 1};
    behind_wall.fovy_degrees = open.fovy_degrees = 90.0f;
    behind_wall.near_plane = open.near_plane = 0.5f;
    const Frame walled(behind_wall, 96, 96), opened(open, 96, 96);
    const auto budgets = [&](bool adapt, std::size_t least, const std::vector<const Frame *> &frames) {
        Settings settings("test", &s);
        settings.set("occluder-triangles", "512");
        settings.set("coverage", "merged");
        settings.set("adapt-triangles", adapt ? "on" : "off");
        TriangleOccluders occluders(scene, settings, least);
        std::vector<std::size_t> out;
        for (const Frame *frame : frames) {
            DepthRasterizer raster;
            raster.begin(frame->view_projection, 96, 96, {2, true, true});
            const std::size_t drawn = occluders.render(*frame, raster);
            EXPECT_LE(drawn, out.empty() ? 512u : out.back());
            out.push_back(occluders.budget());
        }
        return out;
    };
    std::vector<const Frame *> route = {&walled, &walled};
    route.insert(route.end(), 12, &opened);
    route.push_back(&walled);
    const std::vector<std::size_t> adapted = budgets(true, 0, route);
    // Behind the wall only the wall reaches past the buffer.
    EXPECT_EQ(adapted[0], TriangleOccluders::adapted_least);
    EXPECT_EQ(adapted[1], TriangleOccluders::adapted_least);
    // In the open every one drawn reaches: a quarter more a frame, rounded
    // up, up to occluder-triangles.
    std::size_t expected = TriangleOccluders::adapted_least;
    for (std::size_t frame = 2; frame < 14; ++frame) {
        expected = std::min<std::size_t>(512, expected + (expected + 3) / 4);
        EXPECT_EQ(adapted[frame], expected) << "frame " << frame;
    }
    EXPECT_EQ(adapted[13], 512u);
    EXPECT_EQ(adapted[14], TriangleOccluders::adapted_least);
    for (std::size_t b : budgets(false, 0, route))
        EXPECT_EQ(b, 512u) << "adapt-triangles=off: the budget every frame";
    for (std::size_t b : budgets(true, 512, route))
        EXPECT_EQ(b, 512u) << "a least budget of occluder-triangles: nothing to adapt";
    // Off, the frames are today's: the same triangles as with no setting.
    {
        Settings fixed("test", &s), plain("test", &s);
        fixed.set("occluder-triangles", "512");
        fixed.set("adapt-triangles", "off");
        plain.set("occluder-triangles", "512");
        TriangleOccluders a(scene, fixed), b(scene, plain);
        for (const Frame *frame : route)
            EXPECT_EQ(a.choose(*frame), b.choose(*frame));
    }
}
