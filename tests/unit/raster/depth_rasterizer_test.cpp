// SPDX-License-Identifier: MIT
// The CPU depth rasterizer against GL: every depth pixel it covers is
// covered in GL's full-resolution rendering of the same polygons, with
// GL's depth no farther than the rasterizer's at every frame pixel in it;
// its scalar and AVX2 loops agree bit for bit; its rectangle test equals a
// brute-force scan of the buffer.
#include "raster/depth_rasterizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "camera/camera.h"
#include "camera/footprint.h"
#include "gl/gl_headers.h"
#include "gl/offscreen_context.h"
#include "raster/occludee_kernels.h"
#include "raster/raster_kernels.h"

using namespace occu;

namespace {

constexpr int frame_size = 128;

Camera test_camera()
{
    Camera c;
    c.position = {0, 0, 0};
    c.target = {0, 0, -1};
    c.near_plane = 0.1f;
    c.far_plane = 50.0f;
    return c;
}

// Whether the occludee test hides the triangle v[0], v[1], v[2].
bool triangle_hidden(const DepthRasterizer &r, const glm::vec3 *v)
{
    const DepthRasterizer::TriangleCorners corners{&v[0], &v[1], &v[2]};
    return r.first_shown(&corners, 1) == 1;
}

struct Polygons {
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> triangles, quads;   // indices, 3 and 4 each
};

// Random triangles and planar convex quads in front of (and some across)
// the near plane, large and small, either winding.
Polygons random_polygons(std::mt19937 &rng, int count)
{
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Polygons p;
    for (int i = 0; i < count; ++i) {
        const glm::vec3 centre{unit(rng) * 6 - 3, unit(rng) * 6 - 3, -0.05f - unit(rng) * 10};
        const float size = 0.05f + unit(rng) * unit(rng) * 8.0f;
        const glm::vec3 a = glm::normalize(glm::vec3{unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f});
        glm::vec3 b = glm::cross(a, glm::normalize(glm::vec3{unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f}));
        b = glm::normalize(b);
        const bool quad = unit(rng) < 0.5f;
        const int corners = quad ? 4 : 3;
        // Points on an ellipse in increasing angle: a convex polygon.
        float angle = unit(rng) * 6.28f;
        const float ra = size * (0.3f + unit(rng)), rb = size * (0.3f + unit(rng));
        const auto first = std::uint32_t(p.positions.size());
        for (int k = 0; k < corners; ++k) {
            angle += (6.28f / float(corners)) * (0.6f + 0.4f * unit(rng));
            p.positions.push_back(centre + a * (ra * std::cos(angle)) + b * (rb * std::sin(angle)));
        }
        auto &indices = quad ? p.quads : p.triangles;
        for (int k = 0; k < corners; ++k)
            indices.push_back(first + std::uint32_t(k));
    }
    return p;
}

// A rumpled grid of n x n quads, two triangles each sharing their
// vertices, tilted at random, up to `depth` beyond a point just past the
// near plane, facing the eye or away.
Polygons rumpled_grid(std::mt19937 &rng, int n, float depth, bool facing)
{
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::vec3 centre{unit(rng) * 4 - 2, unit(rng) * 4 - 2, -0.05f - unit(rng) * depth};
    const glm::vec3 u = glm::normalize(glm::vec3{unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f});
    const float away = facing ? -1.0f : 1.0f;
    const glm::vec3 v = glm::normalize(glm::cross(u, glm::vec3{unit(rng) - 0.5f, unit(rng) - 0.5f, away}));
    const float size = 1.0f + unit(rng) * 12.0f;
    Polygons p;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            p.positions.push_back(centre + u * (size * (float(i) / float(n) - 0.5f)) +
                                  v * (size * (float(j) / float(n) - 0.5f)) +
                                  glm::cross(u, v) * (0.05f * size * (unit(rng) - 0.5f) / float(n)));
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const auto at = [&](int x, int y) { return std::uint32_t(y * (n + 1) + x); };
            p.triangles.insert(p.triangles.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            p.triangles.insert(p.triangles.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return p;
}

// The corners of p's triangles, three each, for shared_edge_opposites.
std::vector<glm::vec3> triangle_corners(const Polygons &p)
{
    std::vector<glm::vec3> corners;
    for (std::uint32_t i : p.triangles)
        corners.push_back(p.positions[i]);
    return corners;
}

void rasterize(DepthRasterizer &r, const Polygons &p, const glm::mat4 &vp, const DepthRasterizer::Options &o)
{
    r.begin(vp, frame_size, frame_size, o);
    r.render_triangles(p.positions.data(), p.triangles.data(), p.triangles.size() / 3);
    r.render_quads(p.positions.data(), p.quads.data(), p.quads.size() / 4);
}

// GL's depth of the same polygons at full resolution, back faces culled.
std::vector<float> gl_depth(const Polygons &p, const Camera &camera)
{
    glViewport(0, 0, frame_size, frame_size);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixf(&camera.projection()[0][0]);
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixf(&camera.view()[0][0]);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_CULL_FACE);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT);
    glBegin(GL_TRIANGLES);
    for (std::uint32_t i : p.triangles)
        glVertex3fv(&p.positions[i].x);
    glEnd();
    glBegin(GL_QUADS);
    for (std::uint32_t i : p.quads)
        glVertex3fv(&p.positions[i].x);
    glEnd();
    std::vector<float> depth(std::size_t(frame_size) * frame_size);
    glReadPixels(0, 0, frame_size, frame_size, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    return depth;
}

// The frame pixels `draw` shows in white on black, drawn against the
// depth buffer as it stands (the occluders' depth).
template <typename Draw>
long pixels_shown(Draw draw)
{
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glColor3f(1, 1, 1);
    draw();
    std::vector<std::uint8_t> pixels(std::size_t(frame_size) * frame_size * 4);
    glReadPixels(0, 0, frame_size, frame_size, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    long shown = 0;
    for (std::size_t i = 0; i < pixels.size(); i += 4)
        shown += pixels[i] != 0;
    return shown;
}

struct Comparison {
    long covered = 0;        // depth pixels the rasterizer covers
    long gl_covered = 0;     // frame pixels GL covers
    long violations = 0;     // frame pixels under a covered depth pixel where GL is farther or empty
    std::string first;
};

Comparison compare(const DepthRasterizer &r, const std::vector<float> &gl)
{
    Comparison c;
    for (float d : gl)
        c.gl_covered += d < 1.0f;
    const int k = r.divisor();
    for (int y = 0; y < r.height(); ++y)
        for (int x = 0; x < r.width(); ++x) {
            const float cpu = r.depth(x, y);
            if (!(cpu < 1.0f))
                continue;
            ++c.covered;
            for (int fy = y * k; fy < std::min(frame_size, (y + 1) * k); ++fy)
                for (int fx = x * k; fx < std::min(frame_size, (x + 1) * k); ++fx) {
                    const float g = gl[std::size_t(fy) * frame_size + std::size_t(fx)];
                    if (!(g <= cpu)) {
                        if (!c.violations)
                            c.first = "depth pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") = " +
                                      std::to_string(cpu) + ", GL at (" + std::to_string(fx) + ", " +
                                      std::to_string(fy) + ") = " + std::to_string(g);
                        ++c.violations;
                    }
                }
        }
    return c;
}

// Each comparison draws at frame_size in an off-screen context of its own,
// through the test camera, at the divisor the test is instantiated with;
// its random numbers come from a seed of its own and the divisor.
class DepthRasterizerAgainstGl : public ::testing::TestWithParam<int> {
protected:
    std::mt19937 seeded(unsigned seed) const { return std::mt19937(seed + unsigned(divisor)); }

    const int divisor = GetParam();
    gl::OffscreenContext ctx{frame_size, frame_size};
    const Camera camera = test_camera();
    const glm::mat4 vp = camera.view_projection();
    std::uniform_real_distribution<float> unit{0.0f, 1.0f};
    DepthRasterizer r;
};

TEST_P(DepthRasterizerAgainstGl, CoversOnlyWhatGlCoversAndNeverNearer)
{
    std::mt19937 rng = seeded(1234u);
    long covered = 0, gl_covered = 0;
    for (int per_pixel = 0; per_pixel < 2; ++per_pixel)
        for (int trial = 0; trial < 120; ++trial) {
            // One polygon alone, then scenes of many that fuse.
            const Polygons p = random_polygons(rng, trial % 4 == 0 ? 25 : 1);
            rasterize(r, p, vp, {divisor, per_pixel == 1});
            const Comparison c = compare(r, gl_depth(p, camera));
            ASSERT_EQ(c.violations, 0) << "divisor " << divisor << (per_pixel ? " per-pixel" : " per-polygon")
                                       << " trial " << trial << ": " << c.first;
            covered += c.covered;
            gl_covered += c.gl_covered;
        }
    // Conservative, and not trivially: the covered depth pixels hold a
    // fair share of what GL covers (the rest is lost at polygon edges).
    EXPECT_GT(double(covered) * divisor * divisor, 0.5 * double(gl_covered));
}

// Boxes (render_box: their faces and their silhouette) cover only depth
// pixels GL covers at full resolution drawing their faces, never nearer:
// random boxes, some reaching past the guard band or across the near
// plane, alone and in crowds; and corner-on boxes, whose faces leave the
// pixels along their nearest edge to the silhouette.
TEST_P(DepthRasterizerAgainstGl, BoxesCoverOnlyWhatGlCoversAndNeverNearer)
{
    std::mt19937 rng = seeded(4321u);
    long covered = 0, gl_covered = 0;
    for (int per_pixel = 0; per_pixel < 2; ++per_pixel)
        for (int trial = 0; trial < 80; ++trial) {
            Polygons p;
            std::vector<Aabb> boxes;
            for (int b = 0; b < (trial % 4 == 0 ? 12 : 1); ++b) {
                const glm::vec3 centre{unit(rng) * 12 - 6, unit(rng) * 12 - 6, 1.0f - unit(rng) * 14};
                const glm::vec3 half{0.05f + unit(rng) * 3, 0.05f + unit(rng) * 3, 0.05f + unit(rng) * 3};
                boxes.push_back(Aabb::of(centre - half, centre + half));
            }
            r.begin(vp, frame_size, frame_size, {divisor, per_pixel == 1});
            for (const Aabb &box : boxes) {
                r.render_box(box);
                for (const auto &face : aabb_faces)
                    for (int corner : face) {
                        p.quads.push_back(std::uint32_t(p.positions.size()));
                        p.positions.push_back(box.corner(corner));
                    }
            }
            const Comparison c = compare(r, gl_depth(p, camera));
            ASSERT_EQ(c.violations, 0) << "divisor " << divisor << (per_pixel ? " per-pixel" : " per-polygon")
                                       << " trial " << trial << ": " << c.first;
            covered += c.covered;
            gl_covered += c.gl_covered;
        }
    EXPECT_GT(double(covered) * divisor * divisor, 0.5 * double(gl_covered));
}

// A box the box test calls occluded shows no fragment of its faces in GL
// at full resolution behind the same occluders, so nothing inside it can
// show either; and the box test settles more boxes than the rectangle.
TEST_P(DepthRasterizerAgainstGl, BoxTestHidesOnlyBoxesGlHides)
{
    std::mt19937 rng = seeded(77u);
    int by_rect = 0, by_box = 0;
    for (int scene = 0; scene < 30; ++scene) {
        const Polygons p = random_polygons(rng, 40);
        rasterize(r, p, vp, {divisor, true});
        gl_depth(p, camera);   // the occluders' depth stays in GL's depth buffer
        glDepthMask(GL_FALSE);
        for (int b = 0; b < 60; ++b) {
            const glm::vec3 centre{unit(rng) * 8 - 4, unit(rng) * 8 - 4, -1.0f - unit(rng) * 12};
            const glm::vec3 half{0.05f + unit(rng) * 1.5f, 0.05f + unit(rng) * 1.5f, 0.05f + unit(rng) * 1.5f};
            const Aabb box = Aabb::of(centre - half, centre + half);
            const auto footprint = box_footprint(vp, camera.position, box, frame_size, frame_size);
            if (!footprint)
                continue;
            const float z = footprint->window_z_near - 1e-6f;
            const bool rect = r.occluded(footprint->rect, z), whole = r.occluded(box, footprint->rect, z);
            ASSERT_TRUE(!rect || whole) << "the box test starts with the rectangle";
            by_rect += rect;
            by_box += whole;
            if (!whole)
                continue;
            static const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                            {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
            // Its faces drawn white on black behind the occluders' depth.
            const long shown = pixels_shown([&] {
                glBegin(GL_QUADS);
                for (const auto &face : faces)
                    for (int corner : face) {
                        const glm::vec3 v = box.corner(corner);
                        glVertex3f(v.x, v.y, v.z);
                    }
                glEnd();
            });
            ASSERT_EQ(shown, 0) << "scene " << scene << " box " << b << " called occluded shows " << shown
                                << " pixels";
        }
        glDepthMask(GL_TRUE);
    }
    EXPECT_GT(by_rect, 20) << "the scenes hide some boxes";
    EXPECT_GT(by_box, by_rect) << "the box test settles boxes the rectangle does not";
}

// Merged partial coverage (Masked Occlusion Culling's rule): meshes whose
// triangles share edges, rendered with the triangles across their edges
// named, and random polygons that share none, still cover only what GL
// covers and never nearer; and the merge closes the seams along the
// shared edges that covering whole depth pixels leaves.
TEST_P(DepthRasterizerAgainstGl, MergedCoverageCoversOnlyWhatGlCoversAndClosesSeams)
{
    std::mt19937 rng = seeded(4321u);
    long whole = 0, merged = 0, across = 0, gl_covered = 0;
    for (int trial = 0; trial < 40; ++trial) {
        // Grids of 4 to 40 quads a side: up to 80 triangles across 128
        // pixels, so that many are smaller than a depth pixel.
        Polygons p = rumpled_grid(rng, 4 + trial % 10 * 4, trial % 2 ? 8.0f : 1.0f, trial % 5 != 4);
        if (trial % 3 == 0) {
            // With polygons that share no edge, on top.
            const Polygons q = random_polygons(rng, 10);
            const auto base = std::uint32_t(p.positions.size());
            p.positions.insert(p.positions.end(), q.positions.begin(), q.positions.end());
            for (std::uint32_t i : q.triangles)
                p.triangles.push_back(base + i);
            for (std::uint32_t i : q.quads)
                p.quads.push_back(base + i);
        }
        const std::vector<float> gl = gl_depth(p, camera);
        const std::vector<glm::vec3> opposites = shared_edge_opposites(triangle_corners(p));
        for (int mode = 0; mode < 3; ++mode) {
            r.begin(vp, frame_size, frame_size, {divisor, trial % 4 != 1, mode > 0});
            r.render_triangles(p.positions.data(), p.triangles.data(), p.triangles.size() / 3,
                               mode == 2 ? opposites.data() : nullptr);
            r.render_quads(p.positions.data(), p.quads.data(), p.quads.size() / 4);
            const Comparison c = compare(r, gl);
            ASSERT_EQ(c.violations, 0) << "divisor " << divisor << " mode " << mode << " trial " << trial << ": "
                                       << c.first;
            (mode == 0 ? whole : mode == 1 ? merged : across) += c.covered;
        }
        gl_covered += long(std::count_if(gl.begin(), gl.end(), [](float d) { return d < 1.0f; }));
    }
    const double k2 = double(divisor) * divisor;

    // What GL covers and the buffer does not is lost at the meshes'
    // outlines (a depth pixel's width along them) and, without the
    // triangles across, along every shared edge. With them only the
    // outline is lost: over 85% of GL's pixels stay covered (the grids
    // span 10 to 60 depth pixels, so their outlines hold well under 15%
    // of them at the largest divisor).
    EXPECT_GT(double(across) * k2, 0.85 * double(gl_covered)) << "whole " << whole << " merged " << merged;
    EXPECT_GT(across, merged) << "the triangles across close seams the samples alone leave";
    if (divisor > 1) {
        EXPECT_GT(merged, whole) << "samples of a depth pixel fuse across triangles";
    }
}

// A triangle the triangle test calls hidden shows no fragment in GL at
// full resolution behind the same occluders; and the test settles more
// triangles than the box test of each triangle's bounds.
TEST_P(DepthRasterizerAgainstGl, TriangleTestHidesOnlyTrianglesGlHides)
{
    std::mt19937 rng = seeded(91u);
    int by_box = 0, by_triangles = 0;
    for (int scene = 0; scene < 30; ++scene) {
        const Polygons p = random_polygons(rng, 40);
        rasterize(r, p, vp, {divisor, true, scene % 2 == 1});
        gl_depth(p, camera);   // the occluders' depth stays in GL's depth buffer
        glDepthMask(GL_FALSE);
        for (int t = 0; t < 60; ++t) {
            // A small triangle behind or among the occluders, either winding,
            // some reaching in front of the near plane.
            const glm::vec3 c{unit(rng) * 8 - 4, unit(rng) * 8 - 4, 0.5f - unit(rng) * 13};
            glm::vec3 v[3];
            for (glm::vec3 &x : v)
                x = c + glm::vec3{unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f} * (0.2f + unit(rng) * 3.0f);
            const bool hidden = triangle_hidden(r, v);
            Aabb bounds = Aabb::of(v[0], v[0]);
            bounds.expand(v[1]);
            bounds.expand(v[2]);
            const auto footprint = box_footprint(vp, camera.position, bounds, frame_size, frame_size);
            const bool box = footprint && r.occluded(bounds, footprint->rect, footprint->window_z_near - 1e-6f);
            by_box += box;
            by_triangles += hidden && !box;   // the tighter test's own gain
            if (!hidden)
                continue;
            const long shown = pixels_shown([&] {
                glBegin(GL_TRIANGLES);
                for (const glm::vec3 &x : v)
                    glVertex3f(x.x, x.y, x.z);
                glEnd();
            });
            ASSERT_EQ(shown, 0) << "scene " << scene << " triangle " << t << " called hidden shows " << shown
                                << " pixels";
        }
        glDepthMask(GL_TRUE);
    }
    EXPECT_GT(by_box, 20) << "the scenes hide some triangles' boxes";
    EXPECT_GT(by_triangles, 20) << "the triangle test settles triangles their boxes do not";
}

INSTANTIATE_TEST_SUITE_P(Divisors, DepthRasterizerAgainstGl, ::testing::Values(1, 2, 3, 4),
                         [](const auto &info) { return "divisor_" + std::to_string(info.param); });

// The fill's kernels alone on random convex polygons (mostly triangles;
// edges through pixel centres, slivers, depth planes either way) over a
// buffer of random depths and bounds: the AVX2 fill tests a partly covered
// tile's pixels only against the edges the tile is not wholly inside, and
// must write the same depths, tiles and bounds as the scalar fill's every
// edge.
TEST(DepthRasterizer, ScalarAndAvx2FillsAgreeBitForBit)
{
    if (!DepthRasterizer::avx2_supported())
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs here";
    constexpr int tiles_x = 6, tiles_y = 5, width = tiles_x * raster::tile_size, height = tiles_y * raster::tile_size;
    constexpr std::size_t tiles = std::size_t(tiles_x) * tiles_y;
    std::mt19937 rng(4141);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> depth[2], bound[2], original;
    std::vector<std::uint8_t> dirty[2];
    long written = 0, partly = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        for (int i = 0; i < 2; ++i) {
            depth[i].assign(tiles * raster::tile_pixels, 1.0f);
            bound[i].assign(tiles, 1.0f);
            dirty[i].assign(tiles, 0);
        }
        std::mt19937 fill_rng{unsigned(trial)};
        for (float &d : depth[0])
            d = 0.5f + 0.5f * unit(fill_rng);
        for (float &b : bound[0])
            b = unit(fill_rng) < 0.2f ? 0.6f : 1.0f;
        depth[1] = depth[0];
        bound[1] = bound[0];
        original = depth[0];
        // A convex counter-clockwise polygon (mostly triangles; else up to
        // seven corners, as clipping makes), corners on a sixteenth grid
        // (edges exactly through pixels) or anywhere, some far larger than
        // the buffer.
        const int n = trial % 4 == 3 ? 4 + trial / 4 % 4 : 3;
        const double reach = trial % 5 == 0 ? 3.0 * width : 0.6 * width;
        const glm::dvec2 centre{unit(rng) * width, unit(rng) * height};
        double angle[8];
        for (int i = 0; i < n; ++i)
            angle[i] = unit(rng) * 6.283185307179586;
        std::sort(angle, angle + n);
        const double radius = 0.5 * reach * (0.3 + unit(rng));
        glm::dvec2 v[8];
        for (int i = 0; i < n; ++i) {
            v[i] = centre + glm::dvec2{std::cos(angle[i]), std::sin(angle[i])} * radius;
            if (trial % 3 == 0)
                v[i] = glm::floor(v[i] * 16.0) / 16.0;
        }
        raster::PolygonSetup s{};
        s.edges = n;
        double lo_x = v[0].x, hi_x = v[0].x, lo_y = v[0].y, hi_y = v[0].y;
        for (int e = 0; e < n; ++e) {
            const glm::dvec2 p = v[e], q = v[(e + 1) % n];
            const double a = p.y - q.y, b = q.x - p.x, c = -(a * p.x + b * p.y);
            s.ea[e] = float(a);
            s.eb[e] = float(b);
            s.ec[e] = float(c - (trial % 2 ? 0.0 : 0.25 * (std::abs(a) + std::abs(b))));
            lo_x = std::min(lo_x, p.x);
            hi_x = std::max(hi_x, p.x);
            lo_y = std::min(lo_y, p.y);
            hi_y = std::max(hi_y, p.y);
        }
        s.za = (unit(rng) - 0.5f) * 0.01f;
        s.zb = (unit(rng) - 0.5f) * 0.01f;
        s.zc = 0.4f + 0.5f * unit(rng);
        s.zcap = 0.95f;
        s.x0 = std::max(0, int(std::floor(lo_x)));
        s.y0 = std::max(0, int(std::floor(lo_y)));
        s.x1 = std::min(width, int(std::ceil(hi_x)) + 1);
        s.y1 = std::min(height, int(std::ceil(hi_y)) + 1);
        if (s.x0 >= s.x1 || s.y0 >= s.y1)
            continue;
        for (int i = 0; i < 2; ++i) {
            const raster::TileBuffer buffer{depth[i].data(), dirty[i].data(), bound[i].data(), tiles_x};
            (i == 0 ? raster::fill_scalar : raster::fill_avx2)(s, buffer);
        }
        ASSERT_EQ(std::memcmp(depth[0].data(), depth[1].data(), depth[0].size() * sizeof(float)), 0) << "trial " << trial;
        ASSERT_EQ(std::memcmp(bound[0].data(), bound[1].data(), bound[0].size() * sizeof(float)), 0) << "trial " << trial;
        // Tiles marked: every tile the scalar fill marks (those it wrote);
        // the AVX2 fill also marks each wholly covered tile it fills.
        for (std::size_t t = 0; t < tiles; ++t)
            ASSERT_TRUE(!dirty[0][t] || dirty[1][t]) << "trial " << trial << " tile " << t;
        // Tiles written in some pixels and not others: partly covered.
        for (std::size_t t = 0; t < tiles; ++t) {
            int changed = 0;
            for (int i = 0; i < raster::tile_pixels; ++i)
                changed += depth[0][t * raster::tile_pixels + std::size_t(i)] != original[t * raster::tile_pixels + std::size_t(i)];
            ASSERT_TRUE(changed == 0 || dirty[0][t]) << "trial " << trial << " tile " << t;
            written += changed > 0;
            partly += changed > 0 && changed < raster::tile_pixels;
        }
    }
    EXPECT_GT(written, 5000) << "the comparison saw tiles written";
    EXPECT_GT(partly, 1000) << "and tiles whose depths differ pixel to pixel";
}

TEST(DepthRasterizer, ScalarAndAvx2BuffersAreEqualBitForBit)
{
    if (!DepthRasterizer::avx2_supported())
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs here";
    const glm::mat4 vp = test_camera().view_projection();
    std::mt19937 rng(99);
    DepthRasterizer scalar(DepthRasterizer::Isa::scalar), avx2(DepthRasterizer::Isa::avx2);
    std::vector<float> a, b;
    long covered = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const Polygons p = random_polygons(rng, 1 + trial % 40);
        const DepthRasterizer::Options o{1 + trial % 4, trial % 3 != 0};
        rasterize(scalar, p, vp, o);
        rasterize(avx2, p, vp, o);
        scalar.read(a);
        avx2.read(b);
        ASSERT_EQ(a.size(), b.size());
        ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "trial " << trial;
        for (float d : a)
            covered += d < 1.0f;
        for (int i = 0; i < 50; ++i) {
            std::uniform_int_distribution<int> coord(-4, frame_size + 4);
            const PixelRect rect{coord(rng), coord(rng), coord(rng), coord(rng)};
            const float z = std::uniform_real_distribution<float>(0.9f, 1.0f)(rng);
            ASSERT_EQ(scalar.occluded(rect, z), avx2.occluded(rect, z));
        }
    }
    EXPECT_GT(covered, 10000) << "the comparison saw covered pixels";
}

// Meshes as the city's: many small triangles sharing vertices, both
// windings, some across the near plane and some outside the view; in one
// call, so that the AVX2 path screens them eight at a time across its
// batches and their ends.
TEST(DepthRasterizer, ScalarAndAvx2AgreeOnLargeMeshesTriangleByTriangle)
{
    if (!DepthRasterizer::avx2_supported())
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs here";
    const glm::mat4 vp = test_camera().view_projection();
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    DepthRasterizer scalar(DepthRasterizer::Isa::scalar), avx2(DepthRasterizer::Isa::avx2);
    std::vector<float> a, b;
    long covered = 0;
    std::uint64_t rasterized = 0, clipped = 0;
    for (int trial = 0; trial < 24; ++trial) {
        const Polygons grid = rumpled_grid(rng, 8 + trial * 3, trial % 2 ? 8.0f : 1.0f, trial % 4 != 3);
        const std::vector<glm::vec3> &positions = grid.positions;
        const std::vector<std::uint32_t> &indices = grid.triangles;
        const std::size_t triangles = indices.size() / 3 - std::size_t(trial % 7);   // ends off the eights
        const DepthRasterizer::Options o{1 + trial % 4, trial % 3 != 0};
        for (DepthRasterizer *r : {&scalar, &avx2}) {
            r->begin(vp, frame_size, frame_size, o);
            r->render_triangles(positions.data(), indices.data(), triangles);
        }
        scalar.read(a);
        avx2.read(b);
        ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "trial " << trial;
        EXPECT_EQ(scalar.stats().polygons, avx2.stats().polygons);
        EXPECT_EQ(scalar.stats().rasterized, avx2.stats().rasterized);
        EXPECT_EQ(scalar.stats().clipped, avx2.stats().clipped);
        rasterized += scalar.stats().rasterized;
        clipped += scalar.stats().clipped;
        for (float d : a)
            covered += d < 1.0f;
    }
    EXPECT_GT(covered, 20000) << "the comparison saw covered pixels";
    EXPECT_GT(rasterized, 3000u);
    EXPECT_GT(clipped, 5u) << "some triangles took the one-at-a-time way";
}

// The occludee tests (a triangle's, a box's faces) take the pixels of a
// tile four at a time in AVX2: the same answers as the scalar loop, for
// triangles behind, among and in front of the occluders, either winding.
TEST(DepthRasterizer, ScalarAndAvx2OccludeeTestsAgree)
{
    if (!DepthRasterizer::avx2_supported())
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs here";
    const glm::mat4 vp = test_camera().view_projection();
    std::mt19937 rng(57);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    DepthRasterizer scalar(DepthRasterizer::Isa::scalar), avx2(DepthRasterizer::Isa::avx2);
    int hidden = 0, shown = 0, boxes_hidden = 0, boxes_shown = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const Polygons p = random_polygons(rng, 40);
        const DepthRasterizer::Options o{1 + trial % 4, true, trial % 2 == 1};
        rasterize(scalar, p, vp, o);
        rasterize(avx2, p, vp, o);
        for (int t = 0; t < 100; ++t) {
            const glm::vec3 c{unit(rng) * 8 - 4, unit(rng) * 8 - 4, 0.5f - unit(rng) * 13};
            glm::vec3 v[3];
            for (glm::vec3 &x : v)
                x = c + glm::vec3{unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f} * (0.2f + unit(rng) * 3.0f);
            const bool a = triangle_hidden(scalar, v);
            ASSERT_EQ(a, triangle_hidden(avx2, v)) << "trial " << trial << " triangle " << t;
            (a ? hidden : shown)++;
            Aabb box = Aabb::of(v[0], v[0]);
            box.expand(v[1]);
            box.expand(v[2]);
            const float z_near = unit(rng);
            const bool b = scalar.faces_occluded(box, z_near);
            ASSERT_EQ(b, avx2.faces_occluded(box, z_near)) << "trial " << trial << " box " << t;
            (b ? boxes_hidden : boxes_shown)++;
        }
    }
    EXPECT_GT(hidden, 200);
    EXPECT_GT(shown, 200);
    EXPECT_GT(boxes_hidden, 100);
    EXPECT_GT(boxes_shown, 100);
}

// Equal bits, or both NaN (a NaN's payload is not compared).
bool same_double(double a, double b)
{
    return std::memcmp(&a, &b, sizeof a) == 0 || (a != a && b != b);
}

// The triangle test's corner stage (window position, sides beyond, the
// bound of GL's transform error, the polygon's inputs from them), four
// triangles a call, one a lane, and a lone triangle, its corners the
// lanes, in AVX2 equal their scalar twin bit for bit: near the origin and up to 1e6 m from it (where the error bound grows
// to pixels), beyond the far plane and the sides, across the near plane and
// with a corner that is not finite.
TEST(DepthRasterizer, ScalarAndAvx2OccludeeTrianglesAgreeBitForBit)
{
    if (!DepthRasterizer::avx2_supported())
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs here";
    const double product_error = 8.0 * std::numeric_limits<float>::epsilon();
    const double depth_margin = 1.0 / (1 << 20);
    std::mt19937 rng(61);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    int tested = 0, skipped = 0, shows = 0, alone_tested = 0;
    for (int i = 0; i < 5000; ++i) {
        Camera c;
        const float scale = std::pow(10.0f, float(i % 7));
        c.position = glm::vec3(unit(rng), unit(rng), unit(rng)) * scale;
        c.target = c.position + glm::vec3(unit(rng), unit(rng), unit(rng));
        c.near_plane = 0.1f;
        c.far_plane = 100.0f;
        const glm::dmat4 m(c.view_projection());
        glm::dmat4 magnitude;
        for (int k = 0; k < 4; ++k)
            magnitude[k] = glm::abs(m[k]);
        glm::vec3 v[raster::occludee_lanes][3];
        const float *corners[raster::occludee_lanes][3];
        for (int l = 0; l < raster::occludee_lanes; ++l) {
            // Half of them ahead of the eye, the others anywhere near it.
            const glm::vec3 ahead = glm::normalize(c.target - c.position) * (50.0f + 45.0f * unit(rng));
            const glm::vec3 centre = c.position + (l % 2 ? glm::vec3(unit(rng), unit(rng), unit(rng)) * 120.0f
                                                         : ahead + glm::vec3(unit(rng), unit(rng), unit(rng)) * 10.0f);
            for (int k = 0; k < 3; ++k) {
                v[l][k] = centre + glm::vec3(unit(rng), unit(rng), unit(rng)) * 10.0f;
                corners[l][k] = &v[l][k].x;
            }
            if ((4 * i + l) % 101 == 0)
                v[l][i % 3].y = std::numeric_limits<float>::quiet_NaN();
        }
        const double sx = 128.0 / (1 + i % 4), sy = 96.0 / (1 + i % 4), edge_grow = 1.0 / 16.0 / (1 + i % 4);
        raster::OccludeePolygons a{}, b{};
        const raster::OccludeeVerdicts va = raster::occludee_triangles_scalar(
            &m[0][0], &magnitude[0][0], product_error, corners, sx, sy, edge_grow, depth_margin, a);
        const raster::OccludeeVerdicts vb = raster::occludee_triangles_avx2(
            &m[0][0], &magnitude[0][0], product_error, corners, sx, sy, edge_grow, depth_margin, b);
        ASSERT_EQ(va.shows, vb.shows) << "call " << i;
        ASSERT_EQ(va.skipped, vb.skipped) << "call " << i;
        ASSERT_EQ(a.corners, 3);
        ASSERT_EQ(b.corners, 3);
        for (int l = 0; l < raster::occludee_lanes; ++l) {
            if ((va.shows | va.skipped) >> l & 1) {
                (va.shows >> l & 1 ? shows : skipped)++;
                continue;
            }
            ++tested;
            ASSERT_TRUE(same_double(a.floor_z[l], b.floor_z[l])) << "call " << i << " lane " << l;
            ASSERT_TRUE(same_double(a.grow[l], b.grow[l])) << "call " << i << " lane " << l;
            for (int k = 0; k < 3; ++k)
                ASSERT_TRUE(same_double(a.x[k][l], b.x[k][l]) && same_double(a.y[k][l], b.y[k][l]) &&
                            same_double(a.z[k][l], b.z[k][l]))
                    << "call " << i << " lane " << l << " corner " << k;
        }
        // Each triangle alone, its corners as the lanes: as the scalar
        // kernel with the triangle in every lane.
        for (int l = 0; l < raster::occludee_lanes; ++l) {
            const float *alone[raster::occludee_lanes][3];
            for (int j = 0; j < raster::occludee_lanes; ++j)
                std::copy(corners[l], corners[l] + 3, alone[j]);
            raster::OccludeePolygons one{}, lone{};
            const raster::OccludeeVerdicts vone = raster::occludee_triangles_scalar(
                &m[0][0], &magnitude[0][0], product_error, alone, sx, sy, edge_grow, depth_margin, one);
            const raster::OccludeeVerdicts vlone = raster::occludee_triangle_avx2(
                &m[0][0], &magnitude[0][0], product_error, corners[l], sx, sy, edge_grow, depth_margin, lone);
            ASSERT_EQ(vone.shows, vlone.shows) << "call " << i << " triangle " << l << " alone";
            ASSERT_EQ(vone.skipped, vlone.skipped) << "call " << i << " triangle " << l << " alone";
            if (vone.shows | vone.skipped)
                continue;
            ++alone_tested;
            for (int j = 0; j < raster::occludee_lanes; ++j) {
                ASSERT_TRUE(same_double(one.floor_z[j], lone.floor_z[j]) && same_double(one.grow[j], lone.grow[j]))
                    << "call " << i << " triangle " << l << " alone, lane " << j;
                for (int k = 0; k < 3; ++k)
                    ASSERT_TRUE(same_double(one.x[k][j], lone.x[k][j]) && same_double(one.y[k][j], lone.y[k][j]) &&
                                same_double(one.z[k][j], lone.z[k][j]))
                        << "call " << i << " triangle " << l << " alone, lane " << j << " corner " << k;
            }
        }
    }
    EXPECT_GT(tested, 5000);    // corners compared
    EXPECT_GT(skipped, 2000);   // with every corner beyond a side
    EXPECT_GT(shows, 2000);     // and triangles across the near plane or not finite
    EXPECT_GT(alone_tested, 5000);
}

// The polygons' setup in lanes (facing, reach, edges, plane) equals its
// scalar twin bit for bit, every lane: triangles and quads of either
// winding, large and sub-pixel, nearly edge-on (within and just beyond the
// area's uncertainty), off the buffer, far from it and not finite.
TEST(DepthRasterizer, ScalarAndAvx2OccludeeSetupsAgreeBitForBit)
{
    if (!DepthRasterizer::avx2_supported())
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs here";
    const double depth_margin = 1.0 / (1 << 20);
    std::mt19937 rng(67);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int away = 0, planar = 0, flat = 0;
    for (int i = 0; i < 20000; ++i) {
        raster::OccludeePolygons a{};
        a.corners = 3 + i % 2;
        const double size = std::pow(10.0, unit(rng) * 6.0 - 3.0);   // 1e-3 to 1e3 depth pixels
        for (int l = 0; l < raster::occludee_lanes; ++l) {
            const double cx = unit(rng) * 160.0 - 16.0, cy = unit(rng) * 120.0 - 12.0;
            const double angle = unit(rng) * 6.3, squash = unit(rng) < 0.3 ? std::pow(10.0, -8.0 * unit(rng)) : 1.0;
            const double direction = unit(rng) < 0.5 ? 1.0 : -1.0;
            for (int k = 0; k < a.corners; ++k) {
                // Points on an ellipse in increasing or decreasing angle,
                // squashed to nearly a line for some.
                const double t = angle + direction * (6.28 / a.corners) * (k + 0.4 * unit(rng));
                a.x[k][l] = cx + size * std::cos(t);
                a.y[k][l] = cy + size * squash * std::sin(t);
                a.z[k][l] = unit(rng);
            }
            if ((4 * i + l) % 97 == 0)
                a.x[l % a.corners][l] = (i % 2 ? 1.0 : -1.0) * std::numeric_limits<double>::infinity();
            if ((4 * i + l) % 89 == 0)
                a.y[l % a.corners][l] = std::numeric_limits<double>::quiet_NaN();
            a.floor_z[l] = unit(rng) - 0.1;
            a.grow[l] = 1.0 / 16.0 / (1 + i % 4) + (unit(rng) < 0.5 ? 0.0 : unit(rng) * 4.0);
        }
        raster::OccludeePolygons b = a;
        raster::occludee_setup_scalar(a, 128.0 / (1 + i % 4), 96.0 / (1 + i % 4), depth_margin);
        raster::occludee_setup_avx2(b, 128.0 / (1 + i % 4), 96.0 / (1 + i % 4), depth_margin);
        ASSERT_EQ(a.away, b.away) << "call " << i;
        for (int l = 0; l < raster::occludee_lanes; ++l) {
            const std::string where = "call " + std::to_string(i) + " lane " + std::to_string(l);
            ASSERT_TRUE(same_double(a.x_lo[l], b.x_lo[l]) && same_double(a.y_lo[l], b.y_lo[l]) &&
                        same_double(a.x_hi[l], b.x_hi[l]) && same_double(a.y_hi[l], b.y_hi[l]))
                << where;
            for (int e = 0; e < a.corners; ++e)
                ASSERT_TRUE(same_double(a.ea[e][l], b.ea[e][l]) && same_double(a.eb[e][l], b.eb[e][l]) &&
                            same_double(a.ec[e][l], b.ec[e][l]))
                    << where << " edge " << e << ": " << a.ec[e][l] << " " << b.ec[e][l];
            ASSERT_TRUE(same_double(a.za[l], b.za[l]) && same_double(a.zb[l], b.zb[l]) && same_double(a.zc[l], b.zc[l]))
                << where << ": " << a.zc[l] << " " << b.zc[l];
            if (a.away >> l & 1)
                ++away;
            else
                (a.za[l] == 0.0 && a.zb[l] == 0.0 ? flat : planar)++;
        }
    }
    EXPECT_GT(away, 8000);     // facing away
    EXPECT_GT(planar, 8000);   // set up with their plane
    EXPECT_GT(flat, 8000);      // nearly edge-on: at floor_z throughout
}

// A batch of triangles (a cluster's) answers as its triangles one at a
// time: the first that shows, in either path, against buffers of random
// occluders; batches of 1 to 16, so that lanes past the end of a batch and
// sets of four after the first are tested.
TEST(DepthRasterizer, ScalarAndAvx2FirstShownAgreeWithOneAtATime)
{
    if (!DepthRasterizer::avx2_supported())
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs here";
    const glm::mat4 vp = test_camera().view_projection();
    std::mt19937 rng(71);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    DepthRasterizer scalar(DepthRasterizer::Isa::scalar), avx2(DepthRasterizer::Isa::avx2);
    int all_hidden = 0, past_the_first_four = 0, at_the_first = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const Polygons p = random_polygons(rng, 40);
        const DepthRasterizer::Options o{1 + trial % 4, true, trial % 2 == 1};
        rasterize(scalar, p, vp, o);
        rasterize(avx2, p, vp, o);
        for (int batch = 0; batch < 60; ++batch) {
            // Neighbours behind the occluders, some among or before them.
            const std::size_t count = 1 + std::size_t(batch % 16);
            const glm::vec3 c{unit(rng) * 8 - 4, unit(rng) * 8 - 4, -2.0f - unit(rng) * 11};
            std::vector<glm::vec3> v(3 * count);
            std::vector<DepthRasterizer::TriangleCorners> corners(count);
            for (std::size_t t = 0; t < count; ++t) {
                const glm::vec3 at = c + glm::vec3{unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f} * 2.0f;
                const float size = unit(rng) < 0.1f ? 3.0f : 0.4f;
                for (int k = 0; k < 3; ++k)
                    v[3 * t + std::size_t(k)] =
                        at + glm::vec3{unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f} * size;
                corners[t] = {&v[3 * t], &v[3 * t + 1], &v[3 * t + 2]};
            }
            std::size_t one_at_a_time = count;
            for (std::size_t t = 0; t < count && one_at_a_time == count; ++t)
                if (!triangle_hidden(scalar, &v[3 * t]))
                    one_at_a_time = t;
            const std::size_t a = scalar.first_shown(corners.data(), count);
            ASSERT_EQ(a, avx2.first_shown(corners.data(), count)) << "trial " << trial << " batch " << batch;
            ASSERT_EQ(a, one_at_a_time) << "trial " << trial << " batch " << batch;
            all_hidden += a == count;
            past_the_first_four += a >= 4 && a < count;
            at_the_first += a == 0;
        }
    }
    EXPECT_GT(all_hidden, 1000);
    EXPECT_GT(past_the_first_four, 100);
    EXPECT_GT(at_the_first, 300);
}

TEST(DepthRasterizer, RectangleTestEqualsAScanOfTheBuffer)
{
    const glm::mat4 vp = test_camera().view_projection();
    std::mt19937 rng(7);
    for (auto isa : {DepthRasterizer::Isa::scalar, DepthRasterizer::best_isa()}) {
        DepthRasterizer r(isa);
        std::vector<float> buffer;
        int occluded = 0, visible = 0;
        for (int trial = 0; trial < 60; ++trial) {
            const int k = 1 + trial % 3;
            rasterize(r, random_polygons(rng, 60), vp, {k, true});
            r.read(buffer);
            for (int i = 0; i < 200; ++i) {
                std::uniform_int_distribution<int> coord(-8, frame_size + 8);
                int x0 = coord(rng), x1 = coord(rng), y0 = coord(rng), y1 = coord(rng);
                if (x0 > x1)
                    std::swap(x0, x1);
                if (y0 > y1)
                    std::swap(y0, y1);
                const PixelRect rect{x0, y0, x0 + (x1 - x0) / (1 + i % 8), y0 + (y1 - y0) / (1 + i % 8)};
                const float z = std::uniform_real_distribution<float>(0.95f, 1.0f)(rng);
                const PixelRect m = rect.clamped({0, 0, frame_size, frame_size}).to_map(k).clamped(
                    {0, 0, r.width(), r.height()});
                bool expected = true;
                for (int y = m.y0; y < m.y1; ++y)
                    for (int x = m.x0; x < m.x1; ++x)
                        expected &= buffer[std::size_t(y) * std::size_t(r.width()) + std::size_t(x)] < z;
                ASSERT_EQ(r.occluded(rect, z), expected) << "trial " << trial << " rect " << rect.x0 << ","
                                                         << rect.y0 << "-" << rect.x1 << "," << rect.y1;
                (expected ? occluded : visible)++;
            }
        }
        EXPECT_GT(occluded, 500);
        EXPECT_GT(visible, 500);
    }
}

TEST(DepthRasterizer, ABoxShowsTheFacesThatFaceTheEyeAndNothingFromInside)
{
    const Camera camera = test_camera();
    DepthRasterizer r;
    r.begin(camera.view_projection(), frame_size, frame_size, {});
    r.render_box(Aabb::of({-1, -1, -6}, {1, 1, -4}));
    // Its front face at z = -4 covers the middle of the view.
    const float middle = r.depth(r.width() / 2, r.height() / 2);
    EXPECT_LT(middle, 1.0f);
    EXPECT_TRUE(r.occluded({60, 60, 68, 68}, middle + 1e-3f));
    EXPECT_FALSE(r.occluded({60, 60, 68, 68}, middle - 1e-3f));
    // From inside a box, every face is a back face.
    r.begin(camera.view_projection(), frame_size, frame_size, {});
    r.render_box(Aabb::of({-5, -5, -5}, {5, 5, 5}));
    EXPECT_FALSE(r.occluded({0, 0, frame_size, frame_size}, 0.999f));
}

// A box seen corner-on, as a street's corner building is from the
// crossing: two faces meet along the edge nearest the eye, and the depth
// pixels the edge crosses are covered by neither face wholly when a depth
// pixel holds several frame pixels. The box hides what lies behind that
// edge all the same, near the eye and a few hundred metres away (where
// window depths of the occluder and of what is 30 m behind it differ by
// some 1e-7), wherever the edge falls within a pixel; a box just in front
// of the edge is not hidden.
TEST(DepthRasterizer, ABoxSeenCornerOnHidesWhatLiesBehindItsNearestEdge)
{
    const glm::vec3 eye(0.0f, 1.7f, 0.0f);
    const glm::vec3 along = glm::normalize(glm::vec3(1.0f, 0.0f, -1.0f));
    // Nearest edge, width and height of the box, nearest to farthest.
    struct Distance {
        float edge, width, height;
    };
    for (const Distance d : {Distance{20.0f, 15.0f, 30.0f}, Distance{300.0f, 40.0f, 60.0f}}) {
        const glm::vec3 edge = eye + along * d.edge;
        const Aabb occluder = Aabb::of({edge.x, 0.0f, edge.z - d.width}, {edge.x + d.width, d.height, edge.z});
        const glm::vec3 behind = eye + along * (d.edge + 2.0f * d.width);
        const glm::vec3 in_front = eye + along * (d.edge - 3.0f);
        const Aabb hidden = Aabb::of({behind.x - 1.0f, 3.0f, behind.z - 1.0f}, {behind.x + 1.0f, 5.0f, behind.z + 1.0f});
        const Aabb shown = Aabb::of({in_front.x - 1.0f, 3.0f, in_front.z - 1.0f}, {in_front.x + 1.0f, 5.0f, in_front.z + 1.0f});
        for (int step = 0; step < 8; ++step) {
            // The view turned by up to two pixels from the edge, in eighths.
            const float turn = float(step) / 4.0f / (0.5f * float(frame_size) / std::tan(glm::radians(30.0f)));
            Camera camera;
            camera.position = eye;
            camera.target = eye + glm::vec3(std::cos(turn) * along.x - std::sin(turn) * along.z, 0.0f,
                                            std::sin(turn) * along.x + std::cos(turn) * along.z);
            camera.near_plane = 0.5f;
            camera.far_plane = 4000.0f;
            const glm::mat4 vp = camera.view_projection();
            for (int divisor = 1; divisor <= 4; ++divisor)
                for (const bool per_pixel : {false, true}) {
                    DepthRasterizer r;
                    r.begin(vp, frame_size, frame_size, {divisor, per_pixel});
                    r.render_box(occluder);
                    const auto behind_footprint = box_footprint(vp, eye, hidden, frame_size, frame_size);
                    const auto front_footprint = box_footprint(vp, eye, shown, frame_size, frame_size);
                    ASSERT_TRUE(behind_footprint && front_footprint);
                    EXPECT_TRUE(r.occluded(hidden, behind_footprint->rect, behind_footprint->window_z_near - 1e-6f))
                        << "edge at " << d.edge << " m, turned " << step << "/8 of two pixels, divisor " << divisor
                        << (per_pixel ? ", per-pixel depth" : ", per-polygon depth");
                    EXPECT_FALSE(r.occluded(shown, front_footprint->rect, front_footprint->window_z_near - 1e-6f))
                        << "edge at " << d.edge << " m, turned " << step << "/8 of two pixels, divisor " << divisor;
                }
        }
    }
}

TEST(DepthRasterizer, PerPolygonDepthIsNeverNearerThanPerPixel)
{
    const glm::mat4 vp = test_camera().view_projection();
    std::mt19937 rng(5);
    DepthRasterizer pixel, polygon;
    std::vector<float> a, b;
    long farther = 0;
    for (int trial = 0; trial < 50; ++trial) {
        const Polygons p = random_polygons(rng, 10);
        rasterize(pixel, p, vp, {2, true});
        rasterize(polygon, p, vp, {2, false});
        pixel.read(a);
        polygon.read(b);
        for (std::size_t i = 0; i < a.size(); ++i) {
            ASSERT_GE(b[i], a[i]) << "trial " << trial << " pixel " << i;
            farther += b[i] > a[i];
        }
    }
    EXPECT_GT(farther, 0) << "one depth per polygon is the coarser rule";
}

TEST(DepthRasterizer, TwoBuffersMergedEqualOneBufferOfAllPolygons)
{
    const glm::mat4 vp = test_camera().view_projection();
    std::mt19937 rng(21);
    DepthRasterizer all, first, second;
    std::vector<float> a, b;
    for (int trial = 0; trial < 20; ++trial) {
        const Polygons p = random_polygons(rng, 30), q = random_polygons(rng, 30);
        const DepthRasterizer::Options o{1 + trial % 3, true};
        rasterize(all, p, vp, o);
        all.render_triangles(q.positions.data(), q.triangles.data(), q.triangles.size() / 3);
        all.render_quads(q.positions.data(), q.quads.data(), q.quads.size() / 4);
        rasterize(first, p, vp, o);
        rasterize(second, q, vp, o);
        first.merge_nearest(second);
        all.read(a);
        first.read(b);
        ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "trial " << trial;
        for (int i = 0; i < 20; ++i) {
            const PixelRect rect{i * 6, i * 3, i * 6 + 20, i * 3 + 30};
            ASSERT_EQ(all.occluded(rect, 0.99f), first.occluded(rect, 0.99f)) << "tile maxima after the merge";
        }
    }
    DepthRasterizer other;
    other.begin(vp, 64, 64, {});
    EXPECT_THROW(first.merge_nearest(other), std::invalid_argument);
}

TEST(DepthRasterizer, SharedEdgeOppositesEqualABruteForceSearch)
{
    std::mt19937 rng(5);
    for (int trial = 0; trial < 50; ++trial) {
        // Corners drawn from a few points, so that edges repeat, reverse,
        // and some appear three times; a NaN corner now and then.
        std::uniform_int_distribution<int> pick(0, 3 + trial % 6);
        std::vector<glm::vec3> points;
        for (int i = 0; i <= 3 + trial % 6; ++i)
            points.push_back({float(i), float(i * i % 5), 0.5f * float(i % 3)});
        std::vector<glm::vec3> corners;
        for (int t = 0; t < 4 + trial; ++t)
            for (int c = 0; c < 3; ++c)
                corners.push_back(trial % 7 == 3 && t == 1 && c == 0 ? glm::vec3(std::nanf(""))
                                                                     : points[std::size_t(pick(rng))]);
        const std::vector<glm::vec3> got = shared_edge_opposites(corners);
        ASSERT_EQ(got.size(), corners.size());
        const auto same = [](const glm::vec3 &a, const glm::vec3 &b) { return std::memcmp(&a, &b, sizeof a) == 0; };
        const std::size_t count = corners.size() / 3;
        for (std::size_t t = 0; t < count; ++t)
            for (int e = 0; e < 3; ++e) {
                const glm::vec3 &a = corners[3 * t + std::size_t(e)], &b = corners[3 * t + std::size_t((e + 1) % 3)];
                int forward = 0, backward = 0;
                glm::vec3 opposite(std::nanf(""));
                for (std::size_t u = 0; u < count; ++u)
                    for (int f = 0; f < 3; ++f) {
                        const glm::vec3 &c = corners[3 * u + std::size_t(f)],
                                        &d = corners[3 * u + std::size_t((f + 1) % 3)];
                        forward += same(c, a) && same(d, b);
                        if (same(c, b) && same(d, a)) {
                            ++backward;
                            opposite = corners[3 * u + std::size_t((f + 2) % 3)];
                        }
                    }
                const bool finite = std::isfinite(a.x + b.x);
                const glm::vec3 &g = got[3 * t + std::size_t(e)];
                if (finite && forward == 1 && backward == 1)
                    EXPECT_TRUE(same(g, opposite)) << "trial " << trial << " triangle " << t << " edge " << e;
                else
                    EXPECT_TRUE(std::isnan(g.x)) << "trial " << trial << " triangle " << t << " edge " << e;
            }
    }
}

TEST(DepthRasterizer, ScalarAndAvx2AgreeWithMergedCoverage)
{
    if (!DepthRasterizer::avx2_supported())
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs here";
    const glm::mat4 vp = test_camera().view_projection();
    std::mt19937 rng(32);
    DepthRasterizer scalar(DepthRasterizer::Isa::scalar), avx2(DepthRasterizer::Isa::avx2);
    std::vector<float> a, b;
    for (int trial = 0; trial < 20; ++trial) {
        const Polygons grid = rumpled_grid(rng, 6 + trial * 2, trial % 2 ? 8.0f : 1.0f, trial % 4 != 3);
        const std::vector<glm::vec3> opposites = shared_edge_opposites(triangle_corners(grid));
        // Divisors 1-8: masks of up to 64 samples, their bits 32-63 too.
        const DepthRasterizer::Options o{1 + trial % 8, trial % 3 != 0, true};
        for (DepthRasterizer *r : {&scalar, &avx2}) {
            r->begin(vp, frame_size, frame_size, o);
            r->render_triangles(grid.positions.data(), grid.triangles.data(), grid.triangles.size() / 3,
                                opposites.data());
        }
        scalar.read(a);
        avx2.read(b);
        ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "trial " << trial;
    }
}

// Far from the origin GL's transform error widens merged coverage's
// margins per triangle (the AVX2 screen bounds it in double lanes, the
// scalar way one corner at a time), up to giving a triangle's samples up:
// both paths still agree bit for bit.
TEST(DepthRasterizer, ScalarAndAvx2AgreeWithMergedCoverageFarFromTheOrigin)
{
    if (!DepthRasterizer::avx2_supported())
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs here";
    std::mt19937 rng(33);
    DepthRasterizer scalar(DepthRasterizer::Isa::scalar), avx2(DepthRasterizer::Isa::avx2);
    std::vector<float> a, b;
    for (const float offset : {0.0f, 1e4f, 1e5f, 1e6f}) {
        Camera camera = test_camera();
        camera.position.x += offset;
        camera.target.x += offset;
        const glm::mat4 vp = camera.view_projection();
        for (int trial = 0; trial < 8; ++trial) {
            Polygons grid = rumpled_grid(rng, 8 + trial * 3, trial % 2 ? 8.0f : 1.0f, true);
            for (glm::vec3 &q : grid.positions)
                q.x += offset;
            const std::vector<glm::vec3> opposites = shared_edge_opposites(triangle_corners(grid));
            const DepthRasterizer::Options o{1 + trial % 4, trial % 3 != 0, true};
            for (DepthRasterizer *r : {&scalar, &avx2}) {
                r->begin(vp, frame_size, frame_size, o);
                r->render_triangles(grid.positions.data(), grid.triangles.data(), grid.triangles.size() / 3,
                                    opposites.data());
            }
            scalar.read(a);
            avx2.read(b);
            ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0)
                << "offset " << offset << " trial " << trial;
        }
    }
}

// The partial layer's walk of a polygon's rows (raster::merge_partial_rows)
// in AVX2 lanes equals its scalar twin bit for bit, on runs, buffers and
// triangles across drawn at random for divisors 1-8 (masks of up to 64
// samples): the same depths, partial masks and depths, tiles marked, and
// triangles across asked for.
TEST(DepthRasterizer, ScalarAndAvx2PartialRowsAgreeBitForBit)
{
    if (!DepthRasterizer::avx2_supported())
        GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs here";
    constexpr int tiles_x = 5, tiles_y = 3, width = tiles_x * raster::tile_size;
    constexpr std::size_t tiles = std::size_t(tiles_x) * tiles_y, pixels = tiles * raster::tile_pixels;
    std::mt19937 rng(71);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const auto chance = [&](float p) { return unit(rng) < p; };
    const auto between = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    struct Layer {
        std::vector<float> depth, partial_depth, tile_max, farthest_bound;
        std::vector<std::uint32_t> mask_lo, mask_hi;
        std::vector<std::uint8_t> dirty, written;
        raster::PartialLayer view()
        {
            return {depth.data(), partial_depth.data(), mask_lo.data(),  mask_hi.data(), tile_max.data(),
                    farthest_bound.data(), dirty.data(), written.data(), tiles_x};
        }
    };
    // The rows' walk as DepthRasterizer::merge_partial calls it: again
    // after each stop, with the triangle across it asked for (some have
    // none); how many times it asked for each.
    const auto walk = [](decltype(&raster::merge_partial_rows_scalar) merge_rows, raster::PartialRows &rows,
                         const raster::RowsRuns &runs, int y, unsigned found, const raster::PartialLayer &layer,
                         const raster::PartialAcross *const *across, int *asked) {
        while ((found = merge_rows(rows, runs, y, found, layer)) != 0) {
            ++asked[rows.wanted];
            rows.across[rows.wanted] = across[rows.wanted];
            rows.asked |= 1u << rows.wanted;
        }
    };
    long taken = 0, filled = 0, across_taken = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const int k = 1 + trial % 8, at_once = raster::rows_at_once(k);
        const std::uint64_t full = k == 8 ? ~std::uint64_t(0) : (std::uint64_t(1) << (k * k)) - 1;
        Layer a;
        a.depth.resize(pixels);
        a.partial_depth.resize(pixels);
        a.mask_lo.resize(pixels);
        a.mask_hi.resize(pixels);
        for (std::size_t i = 0; i < pixels; ++i) {
            a.depth[i] = chance(0.5f) ? 1.0f : unit(rng);
            const std::uint64_t mask = chance(0.5f) ? 0 : (std::uint64_t(rng()) << 32 | rng()) & full;
            a.mask_lo[i] = std::uint32_t(mask);
            a.mask_hi[i] = std::uint32_t(mask >> 32);
            a.partial_depth[i] = unit(rng);
        }
        for (std::size_t t = 0; t < tiles; ++t) {
            const float farthest = *std::max_element(a.depth.begin() + std::ptrdiff_t(t * raster::tile_pixels),
                                                     a.depth.begin() + std::ptrdiff_t((t + 1) * raster::tile_pixels));
            a.dirty.push_back(chance(0.5f));
            a.tile_max.push_back(chance(0.8f) ? farthest : unit(rng));
            a.farthest_bound.push_back(chance(0.8f) ? 1.0f : farthest);
            a.written.push_back(0);
        }
        // Runs along the rows, within the buffer's columns, ragged per
        // sample row and held or in a band in some of them.
        raster::RowsRuns runs{};
        const int columns = width * k;
        for (int l = 0; l < 8; ++l) {
            const int lo = between(-k, columns), hi = between(lo - 2, lo + between(0, 2 * width * k / 3));
            runs.held_lo[l] = lo;
            runs.held_hi[l] = chance(0.1f) ? lo - 1 : hi;
            for (int e = 0; e < 3; ++e) {
                runs.band_lo[e][l] = hi + 1 - between(0, 3 * k);
                runs.band_hi[e][l] = runs.band_lo[e][l] + between(-1, 3 * k);
            }
        }
        for (int e = 0; e < 3; ++e)
            runs.band_lanes[e] = chance(0.7f) ? unsigned(rng()) & 0xffu : 0;
        for (int r = 0; r < at_once; ++r) {
            const int l = r * k;
            runs.first[l] = between(0, columns - 1);
            runs.last[l] = between(runs.first[l], columns - 1);
            runs.whole_first[l] = between(runs.first[l], runs.last[l]);
            runs.whole_last[l] = chance(0.2f) ? runs.whole_first[l] - 1 : between(runs.whole_first[l], runs.last[l]);
        }
        const int y = between(0, tiles_y * raster::tile_size - at_once);
        const unsigned found = unsigned(between(1, (1 << at_once) - 1));
        // A polygon nearly facing the eye, and up to three triangles
        // across, some of them none.
        raster::PartialRows rows{};
        rows.k = k;
        for (int i = 0; i < k; ++i)
            rows.offset[i] = float((i + 0.5) / k);
        rows.full_lo = std::uint32_t(full);
        rows.full_hi = std::uint32_t(full >> 32);
        rows.za = (unit(rng) - 0.5f) * 0.02f;
        rows.zb = (unit(rng) - 0.5f) * 0.02f;
        rows.zc = unit(rng);
        rows.zcap = chance(0.5f) ? 1.0f : unit(rng);
        rows.depth_error = chance(0.5f) ? 0.0 : 1e-6 * unit(rng);
        rows.depth_step = raster::partial_depth_step(rows.depth_error);
        rows.behind = chance(0.3f) ? unit(rng) : 0.0f;
        rows.reciprocal = (std::uint64_t(1) << 32) / std::uint64_t(k) + 1;
        raster::PartialAcross across[3];
        const raster::PartialAcross *set_up[3];
        for (int e = 0; e < 3; ++e) {
            raster::PartialAcross &n = across[e];
            // Both edges through a sample of the band, or near one (the
            // test is >=: a sample on both edges is inside).
            const int r = between(0, at_once - 1), j = between(0, k - 1), l = r * k + j;
            runs.band_lanes[e] |= 1u << l;
            const int c0 = std::max(runs.band_lo[e][l], 0), c = between(c0, std::max(runs.band_hi[e][l], c0));
            const float u = float(c / k) + rows.offset[c % k], v = float(y + r) + rows.offset[j];
            for (int i = 0; i < 2; ++i) {
                n.ea[i] = unit(rng) - 0.5f;
                n.eb[i] = unit(rng) - 0.5f;
                n.held[i] = n.ea[i] * u + n.eb[i] * v;
                if (chance(0.3f))
                    n.held[i] += (unit(rng) - 0.5f) * 4.0f;
            }
            n.depth_error = 1e-6;
            n.depth.za = (unit(rng) - 0.5f) * 0.02f;
            n.depth.zb = (unit(rng) - 0.5f) * 0.02f;
            n.depth.zc = unit(rng);
            n.depth.zcap = 1.0f;
            set_up[e] = chance(0.8f) ? &n : nullptr;
        }
        rows.asked = 0;
        rows.resume_x8 = 0;
        rows.wrote = false;
        raster::PartialRows scalar_rows = rows, avx2_rows = rows;
        int scalar_asked[3] = {}, avx2_asked[3] = {};
        Layer b = a;
        const Layer before = a;
        const raster::PartialLayer scalar_layer = a.view(), avx2_layer = b.view();
        walk(raster::merge_partial_rows_scalar, scalar_rows, runs, y, found, scalar_layer, set_up, scalar_asked);
        walk(raster::merge_partial_rows_avx2, avx2_rows, runs, y, found, avx2_layer, set_up, avx2_asked);
        ASSERT_EQ(scalar_rows.wrote, avx2_rows.wrote) << "trial " << trial;
        const auto same = [](const auto &x, const auto &y) {
            return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof x[0]) == 0;
        };
        ASSERT_TRUE(same(a.depth, b.depth)) << "trial " << trial << " (divisor " << k << ")";
        ASSERT_TRUE(same(a.partial_depth, b.partial_depth)) << "trial " << trial << " (divisor " << k << ")";
        ASSERT_TRUE(same(a.mask_lo, b.mask_lo) && same(a.mask_hi, b.mask_hi)) << "trial " << trial << " (divisor " << k << ")";
        ASSERT_TRUE(same(a.dirty, b.dirty) && same(a.written, b.written)) << "trial " << trial;
        ASSERT_EQ(scalar_rows.asked, avx2_rows.asked) << "trial " << trial;
        for (int e = 0; e < 3; ++e) {
            ASSERT_EQ(scalar_asked[e], avx2_asked[e]) << "trial " << trial;
            ASSERT_LE(scalar_asked[e], 1) << "a triangle across is set up once";
        }
        filled += scalar_rows.wrote;
        for (std::size_t i = 0; i < pixels; ++i)
            taken += a.mask_lo[i] != before.mask_lo[i] || a.mask_hi[i] != before.mask_hi[i];
        across_taken += scalar_rows.asked != 0;
    }
    // The cases the comparison must cover: masks taken, pixels filled,
    // triangles across asked for.
    EXPECT_GT(taken, 10000);
    EXPECT_GT(filled, 100);
    EXPECT_GT(across_taken, 500);
}

// The partial layer's depth bound as one float sum (raster::
// partial_depth_step, which the AVX2 rows' walk takes in its range) equals
// partial_next_up(float(double(z) + error)) for every z of the range: all
// the floats in [1/2, 1) for some errors (none, exact multiples of the
// float spacing, just off a tie, and ties, which have no range), and
// random ones for random errors.
TEST(DepthRasterizer, PartialDepthStepEqualsTheBoundThroughDouble)
{
    const auto bound = [](float z, double error) { return raster::partial_next_up(float(double(z) + error)); };
    const double u = 0x1p-24, tiny = 0x1p-53;
    const double errors[] = {0.0,          tiny,          u / 2 - tiny, u / 2,         u / 2 + tiny, u,
                             u + tiny,     2.5 * u,       3.5 * u - tiny, 3.5 * u + tiny, 1e-7,       3e-7,
                             1.2345678e-6, 7 * u + u / 2, 1e-4,           0x1p-8};
    for (const double error : errors) {
        const raster::PartialDepthStep step = raster::partial_depth_step(error);
        const double units = ((0.5 + error) - 0.5) / u;
        const bool tie = units - std::floor(units) == 0.5;
        if (tie || !(error < 0x1p-8)) {
            EXPECT_GT(step.lo, step.hi) << "error " << error << ": no range";
            continue;
        }
        ASSERT_EQ(step.lo, 0.5f);
        EXPECT_GE(step.hi, 1.0f - float(error) - 3.0f * float(u)) << "error " << error;
        long checked = 0;
        for (float z = step.lo; z <= step.hi; z = std::nextafter(z, 2.0f), ++checked)
            if (z + step.add != bound(z, error))
                FAIL() << "error " << error << ", z " << z;
        EXPECT_GT(checked, 1 << 22);
    }
    std::mt19937 rng(41);
    std::uniform_real_distribution<double> error_of(0.0, 2e-6);
    std::uniform_real_distribution<float> depth_of(0.5f, 1.0f);
    for (int trial = 0; trial < 20000; ++trial) {
        const double error = error_of(rng);
        const raster::PartialDepthStep step = raster::partial_depth_step(error);
        if (step.lo > step.hi)
            continue;
        for (int i = 0; i < 64; ++i) {
            float z = i == 0 ? step.lo : i == 1 ? step.hi : depth_of(rng);
            if (z > step.hi)
                continue;
            ASSERT_EQ(z + step.add, bound(z, error)) << "error " << error << ", z " << z;
        }
    }
}

// merge_partial walks the rows the crossing kernel reports: none from
// y_end on, whose lanes hold rows past the polygon. Level lines that hold
// every column make every row below y_end report, so the answer is known
// exactly for each divisor and each count of rows left.
TEST(DepthRasterizer, CrossingKernelsReportEveryRowBelowTheLastAndNoneFromIt)
{
    for (int k = 1; k <= 8; ++k) {
        double lane_row[8], lane_offset[8];
        const int at_once = raster::rows_at_once(k);
        for (int l = 0; l < 8; ++l) {
            lane_row[l] = l < at_once * k ? l / k : 0;
            lane_offset[l] = (l % k + 0.5) / k;
        }
        raster::Crossings c{};
        c.c_lo = 0;
        c.c_hi = 8 * k - 1;
        c.k = k;
        c.lane_row = lane_row;
        c.lane_offset = lane_offset;
        c.edges = 3;
        c.candidates = 0;
        c.rising_edges = 7;
        for (int e = 0; e < 3; ++e) {
            c.start[e] = 1.0;
            c.slope[e] = 0.0;
            c.rising[e] = true;
            c.level[e] = true;
        }
        const int y = 5;
        for (int left = 1; left <= at_once; ++left) {
            c.y_end = y + left;
            const unsigned expected = (1u << left) - 1;
            raster::RowsRuns runs;
            EXPECT_EQ(raster::partial_rows_runs_scalar(c, y, runs), expected) << "k " << k << ", rows left " << left;
            if (DepthRasterizer::avx2_supported()) {
                EXPECT_EQ(raster::partial_rows_runs_avx2(c, y, runs), expected)
                    << "k " << k << ", rows left " << left;
            }
        }
    }
}

// Two buffers of merged coverage joined: what either half's samples hold
// fuses, and the join still covers only what GL covers.
TEST(DepthRasterizer, MergedCoverageJoinsAcrossBuffers)
{
    gl::OffscreenContext ctx(frame_size, frame_size);
    const Camera camera = test_camera();
    const glm::mat4 vp = camera.view_projection();
    std::mt19937 rng(8);
    DepthRasterizer first, second, all;
    long joined = 0, alone = 0;
    for (int trial = 0; trial < 20; ++trial) {
        const Polygons grid = rumpled_grid(rng, 12 + trial, 4.0f, true);
        const std::vector<glm::vec3> opposites = shared_edge_opposites(triangle_corners(grid));
        const DepthRasterizer::Options o{2, true, true};
        // Every other triangle to each buffer.
        std::vector<std::uint32_t> even, odd;
        std::vector<glm::vec3> even_across, odd_across;
        for (std::size_t t = 0; t < grid.triangles.size() / 3; ++t) {
            auto &to = t % 2 ? odd : even;
            auto &to_across = t % 2 ? odd_across : even_across;
            to.insert(to.end(), grid.triangles.begin() + std::ptrdiff_t(3 * t),
                      grid.triangles.begin() + std::ptrdiff_t(3 * t + 3));
            to_across.insert(to_across.end(), opposites.begin() + std::ptrdiff_t(3 * t),
                             opposites.begin() + std::ptrdiff_t(3 * t + 3));
        }
        first.begin(vp, frame_size, frame_size, o);
        second.begin(vp, frame_size, frame_size, o);
        first.render_triangles(grid.positions.data(), even.data(), even.size() / 3, even_across.data());
        second.render_triangles(grid.positions.data(), odd.data(), odd.size() / 3, odd_across.data());
        alone += compare(first, gl_depth(grid, camera)).covered;
        first.merge_nearest(second);
        const Comparison c = compare(first, gl_depth(grid, camera));
        ASSERT_EQ(c.violations, 0) << "trial " << trial << ": " << c.first;
        joined += c.covered;
    }
    EXPECT_GT(joined, 2 * alone) << "each half alone is mostly seams; joined they cover the grid";
    DepthRasterizer whole;
    whole.begin(vp, frame_size, frame_size, {2, true, false});
    EXPECT_THROW(first.merge_nearest(whole), std::invalid_argument) << "another coverage rule";
}

// A wall across the whole view, two triangles sharing a diagonal, its
// corners from 1.7 to 12 half-viewports out (NDC), inside the guard band
// and past the one it had (2): merged coverage
// holds the diagonal's depth pixels, which neither triangle covers
// wholly, only with the triangle across each (render_triangles'
// `across`). A wall near the eye reaches far past the frame; were it
// clipped there, the clipped polygons would know no triangle across, and
// everything behind the diagonal's column of empty depth pixels would
// show through the wall.
TEST(DepthRasterizer, AWallReachingPastTheFrameLeavesNoSeamAlongItsDiagonal)
{
    gl::OffscreenContext ctx(frame_size, frame_size);
    const Camera camera = test_camera();
    const glm::mat4 vp = camera.view_projection();
    for (const float half : {3.0f, 5.0f, 10.0f, 15.0f})
        for (int turn = 0; turn < 6; ++turn) {
            // The wall 3 m away, turned about the view axis by 15 degree steps.
            const float angle = glm::radians(15.0f * float(turn));
            const glm::vec3 u(std::cos(angle), std::sin(angle), 0.0f), v(-u.y, u.x, 0.0f);
            Polygons wall;
            wall.positions = {glm::vec3(0, 0, -3) - half * u - half * v, glm::vec3(0, 0, -3) + half * u - half * v,
                              glm::vec3(0, 0, -3) + half * u + half * v, glm::vec3(0, 0, -3) - half * u + half * v};
            wall.triangles = {0, 1, 2, 0, 2, 3};
            const std::vector<glm::vec3> opposites = shared_edge_opposites(triangle_corners(wall));
            const std::vector<float> gl = gl_depth(wall, camera);
            for (int divisor = 1; divisor <= 4; ++divisor) {
                DepthRasterizer r;
                r.begin(vp, frame_size, frame_size, {divisor, true, true});
                r.render_triangles(wall.positions.data(), wall.triangles.data(), 2, opposites.data());
                const Comparison c = compare(r, gl);
                EXPECT_EQ(c.violations, 0) << c.first;
                EXPECT_EQ(c.covered, long(r.width()) * r.height())
                    << "the wall " << 2.0f * half << " m wide, turned " << 15 * turn << " degrees, divisor " << divisor;
            }
        }
}

// A triangle nearly edge-on to the eye: which way it faces is decided by
// rounding, GL's (its own float transform, vertices snapped to 1/256
// pixel) and the test's (double, from the float matrix), which need not
// agree. The IFC house's sliver (AC14-FZK-Haus.ifc, 0.6 mm wide, of a strip 1.2 m long)
// seen from random eye 48 of random:100:2026 at 1280 x 720, and that eye
// moved up and down, by 0.1 mm steps up to 2 cm (past where the triangle
// turns to face it, 9 mm up) and by 5 mm steps up to 50 cm: wherever GL
// draws a pixel of it, an empty buffer (nothing in front) must not call it
// hidden, at the divisor map-size 256 gives that frame. The same triangle
// 5 cm wide faces away from the lower eyes by more than rounding: there GL
// draws nothing and the test calls it hidden.
TEST(DepthRasterizer, TriangleTestHidesNoTriangleGlDrawsNearlyEdgeOn)
{
    constexpr int width = 1280, height = 720;
    gl::OffscreenContext ctx(width, height);
    const glm::vec3 sliver[3] = {{7.36762619f, 2.84799981f, -1.89150774f},
                                 {7.36704493f, 2.84798288f, -0.666489601f},
                                 {7.36762619f, 2.84800005f, -0.666489601f}};
    // In the sliver's plane, its short edge 86 times as long.
    const glm::vec3 wide[3] = {sliver[0], sliver[2] + (sliver[1] - sliver[2]) * 86.0f, sliver[2]};
    Camera eye48;
    eye48.position = {11.7529497f, 2.9672823f, -6.65772533f};
    eye48.target = {11.0419703f, 3.1715579f, -5.9848361f};
    eye48.fovy_degrees = 60.0f;
    eye48.aspect = float(width) / float(height);
    eye48.near_plane = 0.0251703914f;
    eye48.far_plane = 50.3407822f;
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_CULL_FACE);
    glClearColor(0, 0, 0, 0);
    glColor3f(1, 1, 1);
    DepthRasterizer r;
    for (const glm::vec3 *v : {sliver, wide}) {
        const char *name = v == sliver ? "the sliver" : "the wide triangle";
        int drawn = 0, hidden = 0, wrongly_hidden = 0;
        std::string first;
        std::vector<float> heights;
        for (int step = -200; step <= 200; ++step)
            heights.push_back(1e-4f * float(step));
        for (int step = -100; step <= 100; ++step)
            heights.push_back(5e-3f * float(step));
        for (float rise : heights) {
            Camera c = eye48;
            const glm::vec3 up{0.0f, rise, 0.0f};
            c.position += up;
            c.target += up;
            glMatrixMode(GL_PROJECTION);
            glLoadMatrixf(&c.projection()[0][0]);
            glMatrixMode(GL_MODELVIEW);
            glLoadMatrixf(&c.view()[0][0]);
            glClear(GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT);
            glBegin(GL_TRIANGLES);
            for (int i = 0; i < 3; ++i)
                glVertex3f(v[i].x, v[i].y, v[i].z);
            glEnd();
            std::vector<std::uint8_t> pixels(std::size_t(width) * height * 4);
            glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
            long shown = 0;
            for (std::size_t i = 0; i < pixels.size(); i += 4)
                shown += pixels[i] != 0;
            r.begin(c.view_projection(), width, height, {5, true, true});
            const bool called_hidden = triangle_hidden(r, v);
            drawn += shown > 0;
            hidden += called_hidden;
            if (shown > 0 && called_hidden && !wrongly_hidden++)
                first = "eye moved up " + std::to_string(rise) + " m: GL draws " + std::to_string(shown) +
                        " pixels";
        }
        EXPECT_EQ(wrongly_hidden, 0) << "an empty buffer hides " << name << " where GL draws it; first: " << first;
        EXPECT_GT(drawn, 0) << "GL draws " << name << " from some of the eyes";
        if (v == wide) {
            EXPECT_GT(hidden, 0) << "from the lower eyes it faces away, and the test says so";
        }
    }
}

// begin() clears the partial layer only where the frame before wrote it:
// a rasterizer begun again, frame after frame (the divisor changing now
// and then), holds what a new one would.
TEST(DepthRasterizer, MergedCoverageForgetsTheFrameBefore)
{
    const glm::mat4 vp = test_camera().view_projection();
    std::mt19937 rng(34);
    DepthRasterizer reused;
    std::vector<float> a, b;
    long partial = 0;
    for (int trial = 0; trial < 12; ++trial) {
        const Polygons grid = rumpled_grid(rng, 6 + trial, trial % 2 ? 8.0f : 1.0f, true);
        const std::vector<glm::vec3> opposites = shared_edge_opposites(triangle_corners(grid));
        const DepthRasterizer::Options o{trial < 8 ? 2 : 1 + trial % 4, true, true};
        DepthRasterizer fresh;
        for (DepthRasterizer *r : {&reused, &fresh}) {
            r->begin(vp, frame_size, frame_size, o);
            r->render_triangles(grid.positions.data(), grid.triangles.data(), grid.triangles.size() / 3,
                                opposites.data());
        }
        reused.read(a);
        fresh.read(b);
        ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "trial " << trial;
        // The partial layer fills pixels here (nearer than whole pixels
        // alone), so masks left from the frame before would show.
        DepthRasterizer whole_only;
        whole_only.begin(vp, frame_size, frame_size, {o.divisor, o.per_pixel_depth, false});
        whole_only.render_triangles(grid.positions.data(), grid.triangles.data(), grid.triangles.size() / 3);
        whole_only.read(a);
        for (std::size_t i = 0; i < a.size(); ++i)
            partial += b[i] < a[i];
    }
    EXPECT_GT(partial, 0) << "the grids fuse samples in the partial layer, which the next frame must not see";
}

TEST(DepthRasterizer, RefusesSizesBelowOne)
{
    DepthRasterizer r;
    EXPECT_THROW(r.begin(glm::mat4(1.0f), 0, 10, {}), std::invalid_argument);
    EXPECT_THROW(r.begin(glm::mat4(1.0f), 10, 10, {0, true}), std::invalid_argument);
    EXPECT_THROW(r.begin(glm::mat4(1.0f), 10, 10, {9, true, true}), std::invalid_argument)
        << "a mask holds 8 x 8 samples at most";
    EXPECT_NO_THROW(r.begin(glm::mat4(1.0f), 10, 10, {8, true, true}));
}

}  // namespace
