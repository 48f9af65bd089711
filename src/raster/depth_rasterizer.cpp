// SPDX-License-Identifier: MIT
#include "raster/depth_rasterizer.h"

#include <emmintrin.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "raster/occludee_kernels.h"
#include "raster/raster_kernels.h"

namespace occu {

namespace {

using raster::max_edges;
using raster::tile_pixels;
using raster::tile_size;

constexpr double guard = raster::guard_band;

// How far GL may place an edge from where we compute it, in frame pixels:
// llvmpipe snaps vertices to 1/256 pixel and transforms in its own float
// order; a sixteenth of a pixel is far above both.
constexpr double edge_margin = 1.0 / 16.0;

// How much nearer than our plane GL's depth at a sample may be: a 24-bit
// depth buffer's step (2^-24), float interpolation in GL and here. 2^-20
// is sixteen such steps.
constexpr double depth_margin = 1.0 / (1 << 20);

// Relative float error of a matrix-vector product, GL's (model-view, then
// projection) or ours: a few roundings of the sum of its terms' magnitudes.
constexpr double product_error = 8.0 * std::numeric_limits<float>::epsilon();

// Relative float error of an edge or depth function evaluated over the
// buffer: a few roundings of the largest term.
constexpr double float_error = 4.0 * std::numeric_limits<float>::epsilon();

// m * (p, 1), summed as (m0 x + m1 y) + (m2 z + m3): written out rather
// than left to glm, because the AVX2 screen (raster_kernels.h) must sum in
// the same order.
glm::vec4 clip_position(const glm::mat4 &m, const glm::vec3 &p)
{
    return (m[0] * p.x + m[1] * p.y) + (m[2] * p.z + m[3]);
}

// Signed distances of clip-space vertex v to the clip planes: near, then
// the guard band's four sides. Inside where >= 0.
double plane_distance(const glm::dvec4 &v, int plane)
{
    switch (plane) {
    case 0: return v.z + v.w;
    case 1: return guard * v.w - v.x;
    case 2: return guard * v.w + v.x;
    case 3: return guard * v.w - v.y;
    default: return guard * v.w + v.y;
    }
}

// The polygon's depth over a depth pixel, as the loops evaluate it:
// min(za X + (zb Y + zc), zcap), the farthest over the pixel's samples
// (first and last: the samples' offsets in a depth pixel), never past the
// farthest vertex (a linear function over a convex polygon peaks at a
// vertex).
void depth_plane(const glm::vec2 *window, const float *depth, int n, double first, double last, double extent,
                 bool per_pixel_depth, raster::PolygonSetup &s)
{
    float farthest = depth[0];
    for (int i = 1; i < n; ++i)
        farthest = std::max(farthest, depth[i]);
    s.zcap = float(double(farthest) + depth_margin);
    if (!per_pixel_depth) {
        s.za = s.zb = 0.0f;
        s.zc = s.zcap;
    } else {
        // The plane through vertex 0 and the pair spanning the largest
        // triangle with it, then lifted so that no vertex lies above it
        // (rounding makes a quad's four points not quite coplanar).
        int best = 1;
        double best_area = 0.0;
        const glm::dvec2 o(window[0]);
        for (int j = 1; j + 1 < n; ++j) {
            const glm::dvec2 u = glm::dvec2(window[j]) - o, v = glm::dvec2(window[j + 1]) - o;
            const double twice = u.x * v.y - u.y * v.x;
            if (twice > best_area) {
                best_area = twice;
                best = j;
            }
        }
        const glm::dvec2 u = glm::dvec2(window[best]) - o, v = glm::dvec2(window[best + 1]) - o;
        const double du = double(depth[best]) - depth[0], dv = double(depth[best + 1]) - depth[0];
        const double za = (du * v.y - dv * u.y) / best_area, zb = (dv * u.x - du * v.x) / best_area;
        double zc = double(depth[0]) - za * o.x - zb * o.y;
        double lift = 0.0;
        for (int i = 0; i < n; ++i)
            lift = std::max(lift, double(depth[i]) - (za * window[i].x + zb * window[i].y + zc));
        zc += lift + za * (za > 0.0 ? last : first) + zb * (zb > 0.0 ? last : first);
        zc += depth_margin + float_error * ((std::abs(za) + std::abs(zb)) * extent + std::abs(zc));
        s.za = float(za);
        s.zb = float(zb);
        s.zc = float(zc);
        if (!std::isfinite(s.za) || !std::isfinite(s.zb) || !std::isfinite(s.zc)) {
            s.za = s.zb = 0.0f;   // a sliver with no usable plane: its farthest vertex
            s.zc = s.zcap;
        }
    }
}

}  // namespace

bool DepthRasterizer::avx2_supported()
{
#if defined(__x86_64__) || defined(__i386__)
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

DepthRasterizer::DepthRasterizer(Isa isa) : isa_(isa)
{
    if (isa == Isa::avx2 && !avx2_supported())
        throw std::invalid_argument("the depth rasterizer's AVX2 path needs a CPU with AVX2");
}

void DepthRasterizer::begin(const glm::mat4 &view_projection, int frame_width, int frame_height,
                            const Options &options)
{
    if (frame_width < 1 || frame_height < 1 || options.divisor < 1)
        throw std::invalid_argument("depth rasterizer: frame " + std::to_string(frame_width) + " x " +
                                    std::to_string(frame_height) + " with divisor " + std::to_string(options.divisor) +
                                    " (each must be at least 1)");
    if (options.merge_partial_coverage && options.divisor > 8)
        throw std::invalid_argument("depth rasterizer: merging partial coverage needs a divisor of 8 or less (" +
                                    std::to_string(options.divisor) + " given: a mask holds at most 64 samples)");
    options_ = options;
    view_projection_ = view_projection;
    view_projection_double_ = glm::dmat4(view_projection);
    for (int c = 0; c < 4; ++c)
        view_projection_magnitude_[c] = glm::abs(view_projection_double_[c]);
    frame_width_ = frame_width;
    frame_height_ = frame_height;
    width_ = (frame_width + options.divisor - 1) / options.divisor;
    height_ = (frame_height + options.divisor - 1) / options.divisor;
    tiles_x_ = (width_ + tile_size - 1) / tile_size;
    tiles_y_ = (height_ + tile_size - 1) / tile_size;
    const std::size_t tiles = std::size_t(tiles_x_) * std::size_t(tiles_y_);
    tiles_.assign(tiles * tile_pixels, 1.0f);
    tile_max_.assign(tiles, 1.0f);
    farthest_bound_.assign(tiles, 1.0f);
    dirty_.assign(tiles, 0);
    any_dirty_ = false;
    if (options.merge_partial_coverage) {
        // Only the tiles the last frame's partial layer wrote need
        // clearing; a pixel's partial depth means nothing while its mask
        // is empty (add_partial), so it is never cleared.
        if (partial_mask_lo_.size() == tiles * tile_pixels && partial_written_.size() == tiles) {
            for (std::size_t t = 0; t < tiles; ++t)
                if (partial_written_[t]) {
                    std::fill_n(partial_mask_lo_.begin() + std::ptrdiff_t(t * tile_pixels), tile_pixels, 0);
                    std::fill_n(partial_mask_hi_.begin() + std::ptrdiff_t(t * tile_pixels), tile_pixels, 0);
                    partial_written_[t] = 0;
                }
        } else {
            partial_mask_lo_.assign(tiles * tile_pixels, 0);
            partial_mask_hi_.assign(tiles * tile_pixels, 0);
            partial_written_.assign(tiles, 0);
        }
        partial_depth_.resize(tiles * tile_pixels);
        const int samples = options.divisor * options.divisor;
        full_mask_ = samples == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << samples) - 1;
        const int k = options.divisor, rows = raster::rows_at_once(k);
        for (int l = 0; l < 8; ++l) {
            lane_row_[l] = l < rows * k ? l / k : 0;
            lane_offset_[l] = (l % k + 0.5) / k;
            sample_offset_[l] = float(lane_offset_[l]);
        }
    }
    stats_ = {};
}

void DepthRasterizer::render_triangles(const glm::vec3 *positions, const std::uint32_t *indices,
                                       std::size_t triangle_count, const glm::vec3 *across)
{
    if (!options_.merge_partial_coverage)
        across = nullptr;
    // One triangle alone (skins_culler draws some so) is quicker one at a
    // time than in a batch of eight lanes with seven idle.
    if (isa_ == Isa::avx2 && triangle_count >= 2) {
        render_triangles_avx2(positions, indices, triangle_count, across);
        return;
    }
    glm::vec4 clip[3];
    for (std::size_t t = 0; t < triangle_count; ++t) {
        for (int i = 0; i < 3; ++i)
            clip[i] = clip_position(view_projection_, positions[indices[3 * t + std::size_t(i)]]);
        if (!options_.merge_partial_coverage) {
            polygon(clip, 3);
            continue;
        }
        const glm::vec3 corners[3] = {positions[indices[3 * t]], positions[indices[3 * t + 1]],
                                      positions[indices[3 * t + 2]]};
        polygon(clip, 3, across ? across + 3 * t : nullptr, transform_error(corners, 3));
    }
}

void DepthRasterizer::render_triangles_avx2(const glm::vec3 *positions, const std::uint32_t *indices,
                                            std::size_t triangle_count, const glm::vec3 *across)
{
    // Eight at a time through the setup (raster::screen_triangles_avx2);
    // those that need clipping go on one at a time. With merged partial
    // coverage the screen keeps the triangles that cover no depth pixel
    // wholly, with their corners and transform error, for merge_partial.
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float) && sizeof(glm::mat4) == 16 * sizeof(float),
                  "the AVX2 screen reads positions and the matrix as packed floats");
    constexpr std::size_t batch = 64;
    raster::ScreenedTriangle kept[batch];
    const double k = options_.divisor;
    const raster::TriangleScreen screen{&view_projection_[0][0],
                                        0.5f * float(frame_width_) / float(options_.divisor),
                                        0.5f * float(frame_height_) / float(options_.divisor),
                                        width_,
                                        height_,
                                        options_.per_pixel_depth,
                                        0.5 / k,
                                        (k - 0.5) / k,
                                        edge_margin / k,
                                        guard * std::max(width_, height_) + tile_size,
                                        float_error,
                                        depth_margin,
                                        options_.merge_partial_coverage,
                                        product_error,
                                        0.5 * double(frame_width_) / options_.divisor,
                                        0.5 * double(frame_height_) / options_.divisor,
                                        tiles_.data(),
                                        tile_max_.data(),
                                        dirty_.data(),
                                        tiles_x_};
    const raster::TileBuffer buffer{tiles_.data(), dirty_.data(), farthest_bound_.data(), tiles_x_};
    for (std::size_t first = 0; first < triangle_count; first += batch) {
        const std::size_t count = std::min(batch, triangle_count - first);
        const std::uint32_t *batch_indices = indices + 3 * first;
        const std::size_t n = raster::screen_triangles_avx2(screen, &positions[0].x, batch_indices, count, kept);
        stats_.polygons += count;
        for (std::size_t i = 0; i < n; ++i) {
            const raster::ScreenedTriangle &t = kept[i];
            const glm::vec3 *t_across = across ? across + 3 * (first + t.triangle) : nullptr;
            if (t.set_up && options_.merge_partial_coverage) {
                const glm::vec2 window[3] = {{t.wx[0], t.wy[0]}, {t.wx[1], t.wy[1]}, {t.wx[2], t.wy[2]}};
                if (behind_everything(window, t.depth, 3))
                    continue;
                ++stats_.rasterized;
                draw(window, t.depth, 3, t.setup, t_across, {t.error_window, t.error_depth});
                continue;
            }
            if (t.set_up) {
                ++stats_.rasterized;
                raster::fill_avx2(t.setup, buffer);
                any_dirty_ = true;
                continue;
            }
            glm::vec4 clip[3];
            glm::vec3 corners[3];
            for (int v = 0; v < 3; ++v) {
                corners[v] = positions[batch_indices[3 * t.triangle + std::uint32_t(v)]];
                clip[v] = clip_position(view_projection_, corners[v]);
            }
            --stats_.polygons;   // polygon counts it
            if (options_.merge_partial_coverage)
                polygon(clip, 3, t_across, transform_error(corners, 3));
            else
                polygon(clip, 3);
        }
    }
}

void DepthRasterizer::render_quads(const glm::vec3 *positions, const std::uint32_t *indices, std::size_t quad_count)
{
    glm::vec4 clip[4];
    for (std::size_t q = 0; q < quad_count; ++q) {
        glm::vec3 corners[4];
        for (int i = 0; i < 4; ++i) {
            corners[i] = positions[indices[4 * q + std::size_t(i)]];
            clip[i] = clip_position(view_projection_, corners[i]);
        }
        polygon(clip, 4, nullptr, options_.merge_partial_coverage ? transform_error(corners, 4) : TransformError{});
    }
}

void DepthRasterizer::render_box(const Aabb &box)
{
    // aabb_faces wind counter-clockwise seen from outside, so back-face
    // culling after projection keeps the faces that face the eye (section
    // 5's N . L < 0). The faces share their corners: each corner is
    // transformed and, where no face of it needs clipping, put on screen
    // once, as polygon() puts a face's corners, and a face whose area there
    // is not positive (at least three of the six: those facing away) ends
    // before rasterize(), which would end it by the same area after its
    // bounds and its test against the buffer. Faces that need clipping
    // take polygon()'s way, so the buffer is the same bit for bit.
    glm::vec4 corners[8];
    glm::vec3 points[8];
    unsigned outside[8];
    bool clipped[8];
    for (int i = 0; i < 8; ++i) {
        points[i] = box.corner(i);
        const glm::vec4 v = clip_position(view_projection_, points[i]);
        corners[i] = v;
        // polygon()'s outcodes and clip test, per corner.
        outside[i] = unsigned(v.x > v.w) << 0 | unsigned(v.x < -v.w) << 1 | unsigned(v.y > v.w) << 2 |
                     unsigned(v.y < -v.w) << 3 | unsigned(v.z > v.w) << 4 | unsigned(v.z < -v.w) << 5;
        const float g = float(guard) * v.w;
        clipped[i] = v.z < -v.w || v.x > g || v.x < -g || v.y > g || v.y < -g || !(v.w > 0.0f);
    }
    const float sx = 0.5f * float(frame_width_) / float(options_.divisor);
    const float sy = 0.5f * float(frame_height_) / float(options_.divisor);
    glm::vec2 window[8];
    float depth[8];
    for (int i = 0; i < 8; ++i)
        if (!clipped[i]) {
            const float inv = 1.0f / corners[i].w;
            window[i] = {(corners[i].x * inv + 1.0f) * sx, (corners[i].y * inv + 1.0f) * sy};
            depth[i] = corners[i].z * inv * 0.5f + 0.5f;
        }
    // Merged coverage's margins take the whole box's transform error, on
    // first need.
    TransformError error{};
    bool error_known = !options_.merge_partial_coverage;
    for (const auto &face : aabb_faces) {
        unsigned all_out = 63;
        bool needs_clip = false;
        for (int i = 0; i < 4; ++i) {
            all_out &= outside[face[i]];
            needs_clip |= clipped[face[i]];
        }
        const glm::vec4 &first = corners[face[0]];
        if (all_out || !std::isfinite(first.x + first.y + first.z + first.w)) {
            ++stats_.polygons;   // as polygon() counts and drops it
            continue;
        }
        if (!error_known) {
            error = transform_error(points, 8);
            error_known = true;
        }
        if (needs_clip) {
            const glm::vec4 quad[4] = {corners[face[0]], corners[face[1]], corners[face[2]], corners[face[3]]};
            polygon(quad, 4, nullptr, error);
            continue;
        }
        ++stats_.polygons;
        const glm::vec2 face_window[4] = {window[face[0]], window[face[1]], window[face[2]], window[face[3]]};
        // rasterize()'s area, in its order.
        double area = 0.0;
        for (int i = 0; i < 4; ++i) {
            const glm::vec2 &p = face_window[i], &q = face_window[(i + 1) % 4];
            area += double(p.x) * double(q.y) - double(q.x) * double(p.y);
        }
        if (!(area > 0.0))
            continue;
        const float face_depth[4] = {depth[face[0]], depth[face[1]], depth[face[2]], depth[face[3]]};
        rasterize(face_window, face_depth, 4, nullptr, error);
    }
    // Covering whole depth pixels, the faces leave the depth pixels along
    // the edges where they meet uncovered (none holds all its samples in
    // one face), and a box seen corner-on, as a street's corner building
    // is, lets everything behind its nearest edge through. Merged coverage
    // joins the faces' samples there (Masked Occlusion Culling's rule);
    // here the box's silhouette, the hull of its corners on screen (a
    // convex box seen from outside covers exactly that), is drawn too, at
    // its farthest corner's depth, which no point of its faces is beyond.
    if (!options_.merge_partial_coverage)
        silhouette(corners);
}

void DepthRasterizer::silhouette(const glm::vec4 *corners)
{
    // In double: corners beyond the guard band may lie far out.
    const double sx = 0.5 * double(frame_width_) / options_.divisor;
    const double sy = 0.5 * double(frame_height_) / options_.divisor;
    glm::dvec2 window[8];
    float farthest = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec4 &v = corners[i];
        // Every corner in front of the near plane, or the faces alone: a
        // corner behind it has no place on screen (and a box around the
        // eye has corners behind it; none of its faces faces the eye).
        if (!std::isfinite(v.x + v.y + v.z + v.w) || !(v.w > 0.0f) || v.z < -v.w)
            return;
        window[i] = {(double(v.x) / v.w + 1.0) * sx, (double(v.y) / v.w + 1.0) * sy};
        // As polygon() puts each face's corners.
        const float inv = 1.0f / v.w;
        farthest = std::max(farthest, v.z * inv * 0.5f + 0.5f);
    }
    // The hull, counter-clockwise (y up), by Andrew's monotone chain;
    // collinear corners dropped. A box's hull has at most six corners.
    std::sort(window, window + 8, [](const glm::dvec2 &a, const glm::dvec2 &b) {
        return a.x < b.x || (a.x == b.x && a.y < b.y);
    });
    auto turn = [](const glm::dvec2 &o, const glm::dvec2 &a, const glm::dvec2 &b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    glm::dvec2 hull[2 * max_edges], clipped[2 * max_edges];
    int n = 0;
    for (int i = 0; i < 8; ++i) {
        while (n >= 2 && turn(hull[n - 2], hull[n - 1], window[i]) <= 0.0)
            --n;
        hull[n++] = window[i];
    }
    for (int i = 6, lower = n + 1; i >= 0; --i) {
        while (n >= lower && turn(hull[n - 2], hull[n - 1], window[i]) <= 0.0)
            --n;
        hull[n++] = window[i];
    }
    --n;   // the first corner, again at the end
    // Sutherland-Hodgman against the guard band, as polygon() clips: a
    // clipped vertex lies on the hull's edge up to rounding far below the
    // edge margin.
    const double lo[2] = {(1.0 - guard) * sx, (1.0 - guard) * sy}, hi[2] = {(1.0 + guard) * sx, (1.0 + guard) * sy};
    for (int side = 0; side < 4 && n >= 3; ++side) {
        const int axis = side / 2;
        auto inside = [&](const glm::dvec2 &p) { return side % 2 ? hi[axis] - p[axis] : p[axis] - lo[axis]; };
        int m = 0;
        for (int i = 0; i < n; ++i) {
            const glm::dvec2 &p = hull[i], &q = hull[(i + 1) % n];
            const double dp = inside(p), dq = inside(q);
            if (dp >= 0.0)
                clipped[m++] = p;
            if ((dp >= 0.0) != (dq >= 0.0))
                clipped[m++] = p + dp / (dp - dq) * (q - p);
        }
        n = m;
        std::copy(clipped, clipped + n, hull);
    }
    if (n < 3 || n > max_edges)
        return;
    glm::vec2 points[max_edges];
    float depth[max_edges];
    for (int i = 0; i < n; ++i) {
        points[i] = glm::vec2(hull[i]);
        depth[i] = farthest;
    }
    rasterize(points, depth, n);
}

void DepthRasterizer::polygon(const glm::vec4 *clip, int count, const glm::vec3 *across, TransformError error)
{
    ++stats_.polygons;
    // Outside one clip plane with every vertex (the far plane included):
    // GL draws nothing of it.
    unsigned all_out = 63;
    bool needs_clip = false;
    for (int i = 0; i < count; ++i) {
        const glm::vec4 &v = clip[i];
        unsigned out = 0;
        out |= (v.x > v.w) << 0 | (v.x < -v.w) << 1 | (v.y > v.w) << 2 | (v.y < -v.w) << 3 | (v.z > v.w) << 4 |
               (v.z < -v.w) << 5;
        all_out &= out;
        const float g = float(guard) * v.w;
        needs_clip |= v.z < -v.w || v.x > g || v.x < -g || v.y > g || v.y < -g || !(v.w > 0.0f);
    }
    if (all_out)
        return;
    if (!std::isfinite(clip[0].x + clip[0].y + clip[0].z + clip[0].w))
        return;   // a non-finite transform (the caller's matrix or position): nothing to draw

    glm::vec2 window[max_edges];
    float depth[max_edges];
    const float sx = 0.5f * float(frame_width_) / float(options_.divisor);
    const float sy = 0.5f * float(frame_height_) / float(options_.divisor);
    if (!needs_clip) {
        // With every w > 0 the winding on screen is the sign of the
        // determinant of the vertices' (x, y, w): back faces, half of a
        // closed mesh's triangles, end here before any division.
        const glm::vec4 &p = clip[0], &q = clip[1], &r = clip[2];
        const float winding = p.x * (q.y * r.w - q.w * r.y) - p.y * (q.x * r.w - q.w * r.x) +
                              p.w * (q.x * r.y - q.y * r.x);
        if (count == 3 && !(winding > 0.0f))
            return;
        for (int i = 0; i < count; ++i) {
            const float inv = 1.0f / clip[i].w;
            window[i] = {(clip[i].x * inv + 1.0f) * sx, (clip[i].y * inv + 1.0f) * sy};
            depth[i] = clip[i].z * inv * 0.5f + 0.5f;
        }
        rasterize(window, depth, count, across, error);
        return;
    }

    // Sutherland-Hodgman against the near plane and the guard band, in
    // double: a clipped vertex lies on its polygon's edge, up to rounding
    // far below the edge margin.
    ++stats_.clipped;
    glm::dvec4 a[max_edges], b[max_edges];
    int n = count;
    for (int i = 0; i < count; ++i)
        a[i] = glm::dvec4(clip[i]);
    for (int plane = 0; plane < 5 && n > 0; ++plane) {
        int m = 0;
        for (int i = 0; i < n; ++i) {
            const glm::dvec4 &p = a[i], &q = a[(i + 1) % n];
            const double dp = plane_distance(p, plane), dq = plane_distance(q, plane);
            if (dp >= 0.0)
                b[m++] = p;
            if ((dp >= 0.0) != (dq >= 0.0)) {
                const double t = dp / (dp - dq);
                b[m++] = p + t * (q - p);
            }
        }
        n = m;
        for (int i = 0; i < n; ++i)
            a[i] = b[i];
    }
    if (n < 3)
        return;
    for (int i = 0; i < n; ++i) {
        if (!(a[i].w > 0.0))
            return;   // only an orthographic view at w <= 0, which draws nothing
        const double inv = 1.0 / a[i].w;
        window[i] = {float((a[i].x * inv + 1.0) * double(sx)), float((a[i].y * inv + 1.0) * double(sy))};
        depth[i] = float(a[i].z * inv * 0.5 + 0.5);
    }
    rasterize(window, depth, n, nullptr, error);
}

void DepthRasterizer::rasterize(const glm::vec2 *window, const float *depth, int n, const glm::vec3 *across,
                                TransformError error)
{
    glm::vec2 lo = window[0], hi = window[0];
    for (int i = 1; i < n; ++i) {
        lo = glm::min(lo, window[i]);
        hi = glm::max(hi, window[i]);
    }

    // Depth pixel X holds samples at X + (i + 0.5) / k, i < k: the frame
    // pixels' centres. X is covered only if all of them are inside, so X
    // ranges over [lo - first, hi - last] with first = 0.5 / k and last
    // = (k - 0.5) / k. Most triangles of a detailed mesh cover no depth
    // pixel wholly and end here, before any other setup.
    const double k = options_.divisor;
    const double first = 0.5 / k, last = (k - 0.5) / k;
    raster::PolygonSetup s{};
    s.x0 = std::max(0, int(std::ceil(double(lo.x) - first)));
    s.y0 = std::max(0, int(std::ceil(double(lo.y) - first)));
    s.x1 = std::min(width_, int(std::floor(double(hi.x) - last)) + 1);
    s.y1 = std::min(height_, int(std::floor(double(hi.y) - last)) + 1);
    const bool whole_pixels = s.x0 < s.x1 && s.y0 < s.y1;
    if (!whole_pixels && !options_.merge_partial_coverage)
        return;
    if (options_.merge_partial_coverage && behind_everything(window, depth, n))
        return;

    // Front faces wind counter-clockwise in window coordinates (y up).
    double area = 0.0;
    for (int i = 0; i < n; ++i) {
        const glm::vec2 &p = window[i], &q = window[i + 1 == n ? 0 : i + 1];
        area += double(p.x) * double(q.y) - double(q.x) * double(p.y);
    }
    if (!(area > 0.0))
        return;   // a back face or no area
    ++stats_.rasterized;

    // Coordinates are bounded by the guard band; errors scale with them.
    const double extent = guard * std::max(width_, height_) + tile_size;

    // Edge e from p to q: E(u, v) = a u + b v + c, >= 0 on the inside.
    // The smallest E over a pixel's samples is at the sample nearest the
    // edge's outside: first or last on each axis by the signs of a and b.
    s.edges = n;
    for (int e = 0; e < n; ++e) {
        const glm::dvec2 p(window[e]), q(window[e + 1 == n ? 0 : e + 1]);
        const double a = p.y - q.y, b = q.x - p.x, c = -(a * p.x + b * p.y);
        const double folded = c + a * (a > 0.0 ? first : last) + b * (b > 0.0 ? first : last);
        const double margin = (std::abs(a) + std::abs(b)) * (edge_margin / k) +
                              float_error * ((std::abs(a) + std::abs(b)) * extent + std::abs(folded));
        s.ea[e] = float(a);
        s.eb[e] = float(b);
        s.ec[e] = float(folded - margin);
    }

    depth_plane(window, depth, n, first, last, extent, options_.per_pixel_depth, s);
    draw(window, depth, n, s, across, error);
}

bool DepthRasterizer::behind_everything(const glm::vec2 *window, const float *depth, int n) const
{
    // Drawn nearest first, a mesh's later triangles mostly lie behind
    // what is already there: where every depth pixel the polygon (or a
    // sample beyond its shared edges) may reach is nearer than its
    // nearest vertex, it adds nothing.
    glm::vec2 lo = window[0], hi = window[0];
    float nearest = depth[0];
    for (int i = 1; i < n; ++i) {
        lo = glm::min(lo, window[i]);
        hi = glm::max(hi, window[i]);
        nearest = std::min(nearest, depth[i]);
    }
    const int x0 = std::max(0, int(std::floor(double(lo.x))) - 1);
    const int y0 = std::max(0, int(std::floor(double(lo.y))) - 1);
    const int x1 = std::min(width_, int(std::floor(double(hi.x))) + 2);
    const int y1 = std::min(height_, int(std::floor(double(hi.y))) + 2);
    return x0 >= x1 || y0 >= y1 || all_nearer(x0, y0, x1, y1, float(double(nearest) - depth_margin));
}

void DepthRasterizer::draw(const glm::vec2 *window, const float *depth, int n, const raster::PolygonSetup &s,
                           const glm::vec3 *across, TransformError error)
{
    if (s.x0 < s.x1 && s.y0 < s.y1) {
        const raster::TileBuffer buffer{tiles_.data(), dirty_.data(), farthest_bound_.data(), tiles_x_};
        if (isa_ == Isa::avx2)
            raster::fill_avx2(s, buffer);
        else
            raster::fill_scalar(s, buffer);
        any_dirty_ = true;
    }
    if (options_.merge_partial_coverage)
        merge_partial(window, depth, n, s, across, error);
}

DepthRasterizer::TransformError DepthRasterizer::transform_error(const glm::vec3 *points, int count) const
{
    const glm::dmat4 m(view_projection_);
    TransformError e{0.0, 0.0};
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 p(points[i]);
        add_transform_error(m, p, m * glm::dvec4(p, 1.0), e);
    }
    return e;
}

void DepthRasterizer::add_transform_error(const glm::dmat4 &m, const glm::dvec3 &p, const glm::dvec4 &c,
                                          TransformError &e) const
{
    glm::dvec4 bound;
    for (int r = 0; r < 4; ++r)
        bound[r] = product_error *
                   (std::abs(m[0][r] * p.x) + std::abs(m[1][r] * p.y) + std::abs(m[2][r] * p.z) + std::abs(m[3][r]));
    if (!(c.w > bound.w)) {
        // w itself uncertain: nothing known of where GL puts it.
        e.window = e.depth = std::numeric_limits<double>::infinity();
        return;
    }
    const double sx = 0.5 * double(frame_width_) / options_.divisor, sy = 0.5 * double(frame_height_) / options_.divisor;
    const double w = c.w - bound.w;
    e.window = std::max({e.window, sx * (bound.x + std::abs(c.x / c.w) * bound.w) / w,
                         sy * (bound.y + std::abs(c.y / c.w) * bound.w) / w});
    e.depth = std::max(e.depth, 0.5 * (bound.z + std::abs(c.z / c.w) * bound.w) / w);
}

// The polygon's edges as rasterize sets them up, with the same margins,
// but applied to each sample rather than folded to a pixel's worst one
// (merge_partial), and the triangle across each edge where the caller
// named one.
struct DepthRasterizer::PartialEdges {
    const glm::vec2 *window;
    const float *depth;
    int n;
    const glm::vec3 *across;
    TransformError error;
    int k;
    double first, last, extent;
    // Held where a u + b v + held_c >= 0, the edge function at least the
    // margin (in double: set_up_across measures room with them).
    double ea[raster::max_edges], eb[raster::max_edges], held_c[raster::max_edges], margin[raster::max_edges];
    // The reach: the constant below which no sample is held at all (the
    // margin beyond a shared edge, held_c elsewhere).
    double reach_c[raster::max_edges];
    int candidates;   // bit e (e < 3): a triangle lies across edge e
    // The triangle across each edge, where the caller named one GL draws
    // whole (between the near and far planes, inside the guard band) and
    // both face the eye by more than twice the margin: a sample within
    // the margin of the shared edge, inside the other edges of both, is
    // drawn by one of the two. Its two other edges (in float), and
    // its depth plane. Set up on first need (set_up_across): most
    // triangles of a detailed mesh have no sample in the margin of an edge.
    struct Across {
        int state = 0;   // 0: not yet looked at; 1: usable; -1: not
        // depth_error: the transform's, of both triangles' corners.
        raster::PartialAcross setup;
    } neighbour[3];
    // The depth pixels holding a sample the polygon may reach, within the
    // reach of a shared edge too (partial_edges).
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

namespace {

// The float threshold for an edge a u + b v + c >= 0 tested at a sample
// (u, v) = (float(X) + offset[i], float(Y) + offset[j]) as fl(fl(a u) +
// fl(b v)) >= threshold (the triangle across a shared edge, merge_partial):
// -c raised by a bound of the float error and rounded up, so that a sample
// passing in float passes exactly. With unit roundoff eps = 2^-24,
// rounding the coefficients to float (eps |a| |u|, eps |b| |v|), the
// sample coordinates (offset and sum, 2 eps of each term; offsets such as
// 1/6 have no exact float), both products and the sum (eps each of at
// most |a| |u| + |b| |v|) move the value by at most 5 eps (|a| |u| + |b|
// |v|) and terms in eps^2, below 6 eps ((|a| + |b|) extent + |c|), extent
// bounding every sample coordinate (the guard band); float_error is 8 eps.
float float_threshold(double a, double b, double c, double extent)
{
    const double t = -c + float_error * ((std::abs(a) + std::abs(b)) * extent + std::abs(c));
    float f = float(t);
    if (double(f) < t)
        f = raster::partial_next_up(f);
    return f;
}

}  // namespace

DepthRasterizer::PartialEdges DepthRasterizer::partial_edges(const glm::vec2 *window, const float *depth, int n,
                                                             const glm::vec3 *across, TransformError error) const
{
    PartialEdges p;
    p.window = window;
    p.depth = depth;
    p.n = n;
    p.across = across;
    p.error = error;
    const int k = p.k = options_.divisor;
    // 0.5 / k and (k - 0.5) / k, as begin() divided them.
    p.first = lane_offset_[0];
    p.last = lane_offset_[k - 1];
    p.extent = guard * std::max(width_, height_) + tile_size;
    p.candidates = 0;
    for (int e = 0; e < n; ++e) {
        const glm::dvec2 a_point(window[e]), b_point(window[e + 1 == n ? 0 : e + 1]);
        const double a = a_point.y - b_point.y, b = b_point.x - a_point.x, c = -(a * a_point.x + b * a_point.y);
        p.margin[e] = (std::abs(a) + std::abs(b)) * (edge_margin / k + error.window) +
                      float_error * ((std::abs(a) + std::abs(b)) * p.extent + std::abs(c));
        p.ea[e] = a;
        p.eb[e] = b;
        p.held_c[e] = c - p.margin[e];
    }
    if (across && n == 3)
        for (int e = 0; e < 3; ++e)
            if (std::isfinite(across[e].x + across[e].y + across[e].z))
                p.candidates |= 1 << e;
    glm::vec2 lo = window[0], hi = window[0];
    for (int i = 1; i < n; ++i) {
        lo = glm::min(lo, window[i]);
        hi = glm::max(hi, window[i]);
    }
    // A sample beyond a shared edge counts within the reach, margin / |(a,
    // b)| beyond it (a little more for rounding): the box grows by that.
    // Near a sliver's sharp corner such a sample may lie farther along the
    // edge's line, beyond the box; it is left out (coverage lost, never
    // added).
    double grow = 0.0;
    for (int e = 0; e < 3; ++e)
        if (p.candidates >> e & 1)
            grow = std::max(grow, p.margin[e] / std::sqrt(p.ea[e] * p.ea[e] + p.eb[e] * p.eb[e]));
    grow = grow * (1.0 + 1e-6) + 1e-6;
    if (!(grow < 1.0))
        grow = 1.0;
    p.x0 = std::max(0, int(std::ceil(double(lo.x) - grow - p.last)));
    p.y0 = std::max(0, int(std::ceil(double(lo.y) - grow - p.last)));
    p.x1 = std::min(width_, int(std::floor(double(hi.x) + grow - p.first)) + 1);
    p.y1 = std::min(height_, int(std::floor(double(hi.y) + grow - p.first)) + 1);
    for (int e = 0; e < n; ++e)
        p.reach_c[e] = (p.candidates >> e & 1) ? p.held_c[e] + 2.0 * p.margin[e] : p.held_c[e];
    return p;
}

// Inline where merge_partial asks, once per tile row of a band: most asks
// find the triangle already looked at.
inline bool DepthRasterizer::set_up_across(PartialEdges &p, int e) const
{
    const int state = p.neighbour[e].state;
    return state != 0 ? state > 0 : set_up_neighbour(p, e);
}

bool DepthRasterizer::set_up_neighbour(PartialEdges &p, int e) const
{
    PartialEdges::Across &x = p.neighbour[e];
    x.state = -1;
    const int k = p.k;
    // transform_error(&p.across[e], 1), with the matrix begin() converted.
    TransformError far{0.0, 0.0};
    const glm::dvec3 corner(p.across[e]);
    add_transform_error(view_projection_double_, corner, view_projection_double_ * glm::dvec4(corner, 1.0), far);
    if (!(far.window <= p.error.window && far.depth <= p.error.depth) && !(far.window < 1.0 && far.depth < 1e-2))
        return false;
    const double extra = std::max(far.window, p.error.window);
    x.setup.depth_error = std::max(far.depth, p.error.depth);
    const glm::vec4 c = clip_position(view_projection_, p.across[e]);
    const float g = float(guard) * c.w;
    if (!(c.w > 0.0f && c.z > -c.w && c.z < c.w && std::abs(c.x) <= g && std::abs(c.y) <= g))
        return false;
    const float sx = 0.5f * float(frame_width_) / float(k), sy = 0.5f * float(frame_height_) / float(k);
    const float inv = 1.0f / c.w;
    const glm::vec2 r{(c.x * inv + 1.0f) * sx, (c.y * inv + 1.0f) * sy};
    const float r_depth = c.z * inv * 0.5f + 0.5f;
    // Room to spare: the third corners of both triangles lie at least
    // twice the margin from the shared edge, on either side.
    const double length = std::hypot(p.ea[e], p.eb[e]);
    const glm::dvec2 own(p.window[(e + 2) % 3]);
    const double raw_c = p.held_c[e] + p.margin[e];
    const double own_side = p.ea[e] * own.x + p.eb[e] * own.y + raw_c;
    const double other_side = -(p.ea[e] * double(r.x) + p.eb[e] * double(r.y) + raw_c);
    const double room = 2.0 * p.margin[e] + 2.0 * length * (edge_margin / k + extra);
    if (!(own_side > room && other_side > room))
        return false;
    // The triangle across, counter-clockwise: q, p, r for the edge
    // p -> q; its edges p -> r and r -> q.
    const glm::vec2 from_corner = p.window[e], to_corner = p.window[(e + 1) % 3];
    const glm::vec2 tri[3] = {to_corner, from_corner, r};
    const float tri_depth[3] = {p.depth[(e + 1) % 3], p.depth[e], r_depth};
    for (int j = 0; j < 2; ++j) {
        const glm::dvec2 from(tri[j + 1]), to(tri[(j + 2) % 3]);
        const double ta = from.y - to.y, tb = to.x - from.x, tc = -(ta * from.x + tb * from.y);
        const double m = (std::abs(ta) + std::abs(tb)) * (edge_margin / k + extra) +
                         float_error * ((std::abs(ta) + std::abs(tb)) * p.extent + std::abs(tc));
        x.setup.ea[j] = float(ta);
        x.setup.eb[j] = float(tb);
        x.setup.held[j] = float_threshold(ta, tb, tc - m, p.extent);
    }
    depth_plane(tri, tri_depth, 3, p.first, p.last, p.extent, options_.per_pixel_depth, x.setup.depth);
    x.state = 1;
    return true;
}


void DepthRasterizer::merge_partial(const glm::vec2 *window, const float *depth, int n, const raster::PolygonSetup &s,
                                    const glm::vec3 *across, TransformError error)
{
    if (!(error.window < 1.0 && error.depth < 1e-2))
        return;   // GL may put the polygon a pixel away: its samples say nothing
    PartialEdges p = partial_edges(window, depth, n, across, error);
    if (p.x0 >= p.x1 || p.y0 >= p.y1)
        return;
    const int k = p.k;
    // Sample column c of a row (c / k its depth pixel) lies at u = (c +
    // 0.5) / k. Along a sample row v an edge a u + b v + c holds the
    // samples on one side of its crossing point: one run of columns, found
    // from that point, met with the other edges' runs and turned into
    // each pixel's mask, rather than the samples tested one by one
    // (Hasselgren et al. 2016: a tile row's coverage from its edges'
    // crossings). The crossing, in double, is moved inwards by a bound of
    // its rounding, so a sample in the run has the exact edge function at
    // least the margin there.
    raster::Crossings c;
    c.c_lo = p.x0 * k;
    c.c_hi = p.x1 * k - 1;
    c.y_end = p.y1;
    c.k = k;
    c.lane_row = lane_row_;
    c.lane_offset = lane_offset_;
    c.edges = n;
    c.candidates = p.candidates;
    c.rising_edges = 0;
    // The lines (raster::Crossings): edge e's held constant is line e, the
    // reach of an edge with a triangle across a line after the edges, of
    // the same slope.
    int lines = n;
    const auto set_line = [&](int line, int e, double constant) {
        const bool level = p.ea[e] == 0.0;
        c.start[line] = level ? constant : -constant / p.ea[e];
        c.rising[line] = p.ea[e] >= 0.0;
        c.level[line] = level;
    };
    for (int e = 0; e < n; ++e) {
        set_line(e, e, p.held_c[e]);
        c.slope[e] = p.ea[e] == 0.0 ? p.eb[e] : -p.eb[e] / p.ea[e];
        if (p.ea[e] >= 0.0)
            c.rising_edges |= 1u << e;
    }
    for (int e = 0; e < 3; ++e)
        if (p.candidates >> e & 1) {
            set_line(lines, e, p.reach_c[e]);
            c.slope[lines] = c.slope[e];
            c.reach_line[e] = lines++;
        }
    float nearest = depth[0];
    for (int i = 1; i < n; ++i)
        nearest = std::min(nearest, depth[i]);
    const float behind = float(double(nearest) - depth_margin);
    const bool avx2 = isa_ == Isa::avx2;
    const auto rows_runs = avx2 ? raster::partial_rows_runs_avx2 : raster::partial_rows_runs_scalar;
    const auto merge_rows = avx2 ? raster::merge_partial_rows_avx2 : raster::merge_partial_rows_scalar;
    raster::RowsRuns runs;
    raster::PartialRows rows;
    rows.k = k;
    std::copy(sample_offset_, sample_offset_ + k, rows.offset);
    rows.full_lo = std::uint32_t(full_mask_);
    rows.full_hi = std::uint32_t(full_mask_ >> 32);
    rows.za = s.za;
    rows.zb = s.zb;
    rows.zc = s.zc;
    rows.zcap = s.zcap;
    // The fill's depth: the farthest over all the pixel's samples, so over
    // those the polygon holds, widened by the transform's error and
    // rounded up.
    rows.depth_error = error.depth;
    rows.depth_step = raster::partial_depth_step(error.depth);
    rows.behind = behind;
    // Sample column c's depth pixel, c / k, by a multiply rather than a
    // division's latency on every row: with reciprocal = 2^32 / k + d, 0 <
    // d <= 1, c reciprocal / 2^32 exceeds c / k by less than 1 / k for 0 <=
    // c < 2^32 / k, so its floor is c / k's; the columns here lie in [0,
    // k (width + 1)].
    rows.reciprocal = (std::uint64_t(1) << 32) / std::uint64_t(k) + 1;
    rows.asked = 0;
    rows.resume_x8 = 0;
    rows.wrote = false;
    const raster::PartialLayer layer{tiles_.data(),           partial_depth_.data(), partial_mask_lo_.data(),
                                     partial_mask_hi_.data(), tile_max_.data(),      farthest_bound_.data(),
                                     dirty_.data(),           partial_written_.data(), tiles_x_};
    // Rows a few at a time (raster::rows_at_once): their runs, then their
    // tile rows in one call, which stops where it first needs a triangle
    // across: set up only where a farther pixel holds a sample of its band
    // (most edges have none).
    const int rows_at_once = raster::rows_at_once(k);
    for (int y_first = p.y0; y_first < p.y1; y_first += rows_at_once) {
        unsigned found = rows_runs(c, y_first, runs);
        while (found) {
            found = merge_rows(rows, runs, y_first, found, layer);
            if (found) {
                const int e = rows.wanted;
                rows.across[e] = set_up_across(p, e) ? &p.neighbour[e].setup : nullptr;
                rows.asked |= 1u << e;
            }
        }
    }
    any_dirty_ = any_dirty_ || rows.wrote;
}

bool DepthRasterizer::add_partial(std::size_t index, std::uint64_t mask, float z)
{
    const std::uint64_t old = partial_mask(index);
    const std::uint64_t joined = old | mask;
    const float farthest = old != 0 ? std::max(partial_depth_[index], z) : z;
    if (joined != full_mask_) {
        partial_mask_lo_[index] = std::uint32_t(joined);
        partial_mask_hi_[index] = std::uint32_t(joined >> 32);
        partial_depth_[index] = farthest;
        partial_written_[index / tile_pixels] = 1;
        return false;
    }
    // Every sample is held no farther than `farthest`; the layer starts
    // again empty, whether or not it was nearer.
    partial_mask_lo_[index] = partial_mask_hi_[index] = 0;
    if (!(farthest < tiles_[index]))
        return false;
    tiles_[index] = farthest;
    return true;
}

void DepthRasterizer::merge_nearest(const DepthRasterizer &other)
{
    if (other.width_ != width_ || other.height_ != height_ || other.tiles_.size() != tiles_.size())
        throw std::invalid_argument("depth rasterizer: merging a buffer of another size");
    if (other.options_.merge_partial_coverage != options_.merge_partial_coverage ||
        other.options_.divisor != options_.divisor)
        throw std::invalid_argument("depth rasterizer: merging a buffer with another coverage rule or divisor");
    if (&other == this)
        return;   // nothing is nearer than itself
    for (std::size_t t = 0; t < dirty_.size(); ++t) {
        // Two buffers, never one: each pixel stored, nearer or not, so that
        // the loop vectorizes.
        float *__restrict to = tiles_.data() + t * tile_pixels;
        const float *__restrict from = other.tiles_.data() + t * tile_pixels;
        int nearer = 0;
        for (int i = 0; i < tile_pixels; ++i) {
            const int from_nearer = from[i] < to[i];
            to[i] = from_nearer ? from[i] : to[i];
            nearer |= from_nearer;
        }
        if (nearer) {
            dirty_[t] = 1;
            any_dirty_ = true;
        }
        farthest_bound_[t] = std::min(farthest_bound_[t], other.farthest_bound_[t]);
        if (!options_.merge_partial_coverage)
            continue;
        // Samples held in either buffer are held no farther than the
        // farther of the two layers' depths.
        for (int i = 0; i < tile_pixels; ++i) {
            const std::size_t index = t * tile_pixels + std::size_t(i);
            const std::uint64_t mask = other.partial_mask(index);
            if (mask && add_partial(index, mask, other.partial_depth_[index])) {
                dirty_[t] = 1;
                any_dirty_ = true;
            }
        }
    }
    stats_.polygons += other.stats_.polygons;
    stats_.rasterized += other.stats_.rasterized;
    stats_.clipped += other.stats_.clipped;
}

bool DepthRasterizer::all_nearer(int x0, int y0, int x1, int y1, float z) const
{
    // Tile by tile, each tile's maximum brought up to date where written;
    // the tiles' padding beyond the buffer holds 1, never nearer.
    for (int ty = y0 / tile_size; ty <= (y1 - 1) / tile_size; ++ty)
        for (int tx = x0 / tile_size; tx <= (x1 - 1) / tile_size; ++tx) {
            const std::size_t t = std::size_t(ty) * std::size_t(tiles_x_) + std::size_t(tx);
            if (dirty_[t])
                refresh_tile_maximum(t);
            if (!(tile_max_[t] < z))
                return false;
        }
    return true;
}

void DepthRasterizer::refresh_tile_maximum(std::size_t t) const
{
    // The largest of its pixels (which hold no NaN): each half row's four
    // lanes at once in SSE2 (x86-64's baseline), then across.
    const float *tile = tiles_.data() + t * tile_pixels;
    __m128 left = _mm_loadu_ps(tile), right = _mm_loadu_ps(tile + 4);
    for (int y = 1; y < tile_size; ++y) {
        left = _mm_max_ps(left, _mm_loadu_ps(tile + y * tile_size));
        right = _mm_max_ps(right, _mm_loadu_ps(tile + y * tile_size + 4));
    }
    __m128 m = _mm_max_ps(left, right);
    m = _mm_max_ps(m, _mm_movehl_ps(m, m));
    m = _mm_max_ss(m, _mm_shuffle_ps(m, m, 1));
    tile_max_[t] = _mm_cvtss_f32(m);
    dirty_[t] = 0;
}

void DepthRasterizer::update_tile_maxima() const
{
    // Sixteen marks a step (SSE2): skins are tested and drawn in turn
    // (occluders/skin_occluders.h), each drawn box marks a few tiles, and
    // the next test scans every tile's mark.
    const std::size_t n = dirty_.size();
    std::size_t t = 0;
    for (; t + 16 <= n; t += 16) {
        const __m128i marks = _mm_loadu_si128(reinterpret_cast<const __m128i *>(dirty_.data() + t));
        for (unsigned set = ~unsigned(_mm_movemask_epi8(_mm_cmpeq_epi8(marks, _mm_setzero_si128()))) & 0xFFFFu;
             set != 0; set &= set - 1)
            refresh_tile_maximum(t + std::size_t(__builtin_ctz(set)));
    }
    for (; t < n; ++t)
        if (dirty_[t])
            refresh_tile_maximum(t);
    any_dirty_ = false;
}

bool DepthRasterizer::occluded(const PixelRect &frame_rect, float z) const
{
    if (!(z == z))
        return false;   // NaN depth: nothing is known
    const PixelRect m = frame_rect.clamped({0, 0, frame_width_, frame_height_})
                            .to_map(options_.divisor)
                            .clamped({0, 0, width_, height_});
    if (m.empty())
        return true;
    if (any_dirty_)
        update_tile_maxima();
    for (int ty = m.y0 / tile_size; ty <= (m.y1 - 1) / tile_size; ++ty)
        for (int tx = m.x0 / tile_size; tx <= (m.x1 - 1) / tile_size; ++tx) {
            const std::size_t t = std::size_t(ty) * std::size_t(tiles_x_) + std::size_t(tx);
            if (tile_max_[t] < z)
                continue;   // the whole tile, padding included, is nearer
            const int c0 = std::max(m.x0 - tx * tile_size, 0), c1 = std::min(m.x1 - tx * tile_size, tile_size);
            const int r0 = std::max(m.y0 - ty * tile_size, 0), r1 = std::min(m.y1 - ty * tile_size, tile_size);
            const float *tile = tiles_.data() + t * tile_pixels;
            const bool behind = isa_ == Isa::avx2 ? raster::tile_behind_avx2(tile, c0, c1, r0, r1, z)
                                                  : raster::tile_behind_scalar(tile, c0, c1, r0, r1, z);
            if (!behind)
                return false;
        }
    return true;
}

bool DepthRasterizer::occluded(const Aabb &box, const PixelRect &frame_rect, float z_near) const
{
    return occluded(frame_rect, z_near) || faces_occluded(box, z_near);
}

bool DepthRasterizer::faces_occluded(const Aabb &box, float z_near) const
{
    if (!(z_near == z_near))
        return false;
    // The corners in window coordinates of the buffer (depth pixels) and
    // window depth, in double: this test decides what is not drawn.
    const double k = options_.divisor;
    const double sx = 0.5 * double(frame_width_) / k, sy = 0.5 * double(frame_height_) / k;
    double window_x[8], window_y[8], corner_depth[8];
    if (isa_ == Isa::avx2) {
        if (!raster::box_corners_window_avx2(&view_projection_double_[0][0], &box.min.x, &box.max.x, sx, sy, window_x,
                                             window_y, corner_depth))
            return false;   // in front of the near plane, or around the eye
    } else {
        for (int i = 0; i < 8; ++i) {
            const glm::dvec4 c = view_projection_double_ * glm::dvec4(glm::dvec3(box.corner(i)), 1.0);
            if (!(c.w > 0.0) || c.z < -c.w)
                return false;
            window_x[i] = (c.x / c.w + 1.0) * sx;
            window_y[i] = (c.y / c.w + 1.0) * sy;
            corner_depth[i] = c.z / c.w * 0.5 + 0.5;
        }
    }
    // The box's content can be nearer than its faces nowhere, and nearer
    // than its nearest corner nowhere: both bounds less the depth margin.
    // The six faces in two sets of lanes, the second set up only where
    // the first four are hidden.
    const double floor_z = double(z_near) - depth_margin;
    if (any_dirty_)
        update_tile_maxima();
    raster::OccludeePolygons p;
    p.corners = 4;
    constexpr int faces = int(std::size(aabb_faces));
    for (int first = 0; first < faces; first += raster::occludee_lanes) {
        for (int l = 0; l < raster::occludee_lanes; ++l) {
            const auto &face = aabb_faces[std::min(first + l, faces - 1)];
            for (int i = 0; i < 4; ++i) {
                p.x[i][l] = window_x[face[i]];
                p.y[i][l] = window_y[face[i]];
                p.z[i][l] = corner_depth[face[i]];
            }
            p.floor_z[l] = floor_z;
            p.grow[l] = edge_margin / k;
        }
        occludee_setup(p);
        // A face facing away is skipped: the faces that face the eye cover
        // the box's silhouette.
        for (int l = 0; l < std::min(raster::occludee_lanes, faces - first); ++l)
            if (!(p.away >> l & 1) && !polygon_behind(p, l))
                return false;
    }
    return true;
}

std::size_t DepthRasterizer::first_shown(const TriangleCorners *triangles, std::size_t count) const
{
    const double k = options_.divisor;
    const double sx = 0.5 * double(frame_width_) / k, sy = 0.5 * double(frame_height_) / k;
    const glm::dmat4 &m = view_projection_double_, &magnitude = view_projection_magnitude_;
    if (any_dirty_)
        update_tile_maxima();
    raster::OccludeePolygons p;
    for (std::size_t first = 0; first < count; first += raster::occludee_lanes) {
        // Each corner's window position, and the bound of GL's float error
        // from its clip coordinates: add_transform_error's, each row's sum
        // of magnitudes taken as one product of magnitudes (|m| |p|; only
        // the order of the additions differs, far below product_error's
        // slack). Lanes past the end repeat the last triangle.
        const int lanes = int(std::min<std::size_t>(raster::occludee_lanes, count - first));
        const float *corners[raster::occludee_lanes][3];
        for (int l = 0; l < raster::occludee_lanes; ++l)
            for (int i = 0; i < 3; ++i)
                corners[l][i] = &triangles[first + std::size_t(std::min(l, lanes - 1))][i]->x;
        // A lone triangle (the one a leaf showed last, a cluster's last)
        // takes its corners as the lanes instead.
        const raster::OccludeeVerdicts verdicts =
            isa_ != Isa::avx2 ? raster::occludee_triangles_scalar(&m[0][0], &magnitude[0][0], product_error, corners,
                                                                  sx, sy, edge_margin / k, depth_margin, p)
            : lanes == 1      ? raster::occludee_triangle_avx2(&m[0][0], &magnitude[0][0], product_error, corners[0],
                                                               sx, sy, edge_margin / k, depth_margin, p)
                              : raster::occludee_triangles_avx2(&m[0][0], &magnitude[0][0], product_error, corners, sx,
                                                                sy, edge_margin / k, depth_margin, p);
        const unsigned used = (1u << lanes) - 1;
        if (((verdicts.shows | verdicts.skipped) & used) != used)
            occludee_setup(p);
        for (int l = 0; l < lanes; ++l) {
            if (verdicts.shows >> l & 1)
                return first + std::size_t(l);
            if (verdicts.skipped >> l & 1 || p.away >> l & 1)
                continue;
            if (!polygon_behind(p, l))
                return first + std::size_t(l);
        }
    }
    return count;
}

void DepthRasterizer::occludee_setup(raster::OccludeePolygons &p) const
{
    if (isa_ == Isa::avx2)
        raster::occludee_setup_avx2(p, double(width_), double(height_), depth_margin);
    else
        raster::occludee_setup_scalar(p, double(width_), double(height_), depth_margin);
}

bool DepthRasterizer::polygon_behind(const raster::OccludeePolygons &p, int lane) const
{
    const int x0 = std::max(0, int(p.x_lo[lane])), y0 = std::max(0, int(p.y_lo[lane]));
    const int x1 = std::min(width_, int(p.x_hi[lane]) + 1);
    const int y1 = std::min(height_, int(p.y_hi[lane]) + 1);
    if (x0 >= x1 || y0 >= y1)
        return true;
    if (isa_ == Isa::avx2)
        return raster::polygon_behind_avx2(p, lane, tiles_.data(), tile_max_.data(), tiles_x_, x0, y0, x1, y1);
    const double za = p.za[lane], zb = p.zb[lane], zc = p.zc[lane], floor_z = p.floor_z[lane];
    // Tile by tile: a tile whose farthest depth is nearer than the
    // polygon's nearest over the tile settles all its pixels at once.
    for (int ty = y0 / tile_size; ty <= (y1 - 1) / tile_size; ++ty)
        for (int tx = x0 / tile_size; tx <= (x1 - 1) / tile_size; ++tx) {
            const int tx0 = std::max(x0, tx * tile_size), tx1 = std::min(x1, (tx + 1) * tile_size);
            const int ty0 = std::max(y0, ty * tile_size), ty1 = std::min(y1, (ty + 1) * tile_size);
            const double tile_nearest =
                std::max(floor_z, za * (za < 0.0 ? tx1 - 1 : tx0) + zb * (zb < 0.0 ? ty1 - 1 : ty0) + zc);
            const std::size_t t = std::size_t(ty) * std::size_t(tiles_x_) + std::size_t(tx);
            if (double(tile_max_[t]) < tile_nearest)
                continue;
            const float *tile = tiles_.data() + t * tile_pixels;
            for (int y = ty0; y < ty1; ++y)
                for (int x = tx0; x < tx1; ++x) {
                    bool inside = true;
                    for (int e = 0; e < p.corners && inside; ++e)
                        inside = p.ea[e][lane] * x + p.eb[e][lane] * y + p.ec[e][lane] >= 0.0;
                    if (!inside)
                        continue;
                    const double nearest = std::max(floor_z, za * x + zb * y + zc);
                    if (!(double(tile[(y % tile_size) * tile_size + x % tile_size]) < nearest))
                        return false;
                }
        }
    return true;
}

float DepthRasterizer::depth(int x, int y) const
{
    const std::size_t t = std::size_t(y / tile_size) * std::size_t(tiles_x_) + std::size_t(x / tile_size);
    return tiles_[t * tile_pixels + std::size_t(y % tile_size) * tile_size + std::size_t(x % tile_size)];
}

void DepthRasterizer::read(std::vector<float> &out) const
{
    out.resize(std::size_t(width_) * std::size_t(height_));
    for (int y = 0; y < height_; ++y) {
        float *row = out.data() + std::size_t(y) * std::size_t(width_);
        for (int tx = 0; tx < tiles_x_; ++tx) {
            const float *from = tiles_.data() +
                                (std::size_t(y / tile_size) * std::size_t(tiles_x_) + std::size_t(tx)) * tile_pixels +
                                std::size_t(y % tile_size) * tile_size;
            const int x0 = tx * tile_size, count = std::min(tile_size, width_ - x0);
            std::copy(from, from + count, row + x0);
        }
    }
}

}  // namespace occu

namespace occu {

std::vector<glm::vec3> shared_edge_opposites(const std::vector<glm::vec3> &triangles)
{
    // Each directed edge as its corners' bits, sorted, so that an edge and
    // its reverse are found by binary search.
    struct Edge {
        std::array<std::uint32_t, 6> key;
        std::uint32_t corner;   // the corner the edge starts at: 3 t + e
        bool operator<(const Edge &o) const { return key < o.key; }
    };
    const auto bits = [](const glm::vec3 &p, std::uint32_t *out) { std::memcpy(out, &p.x, 3 * sizeof(float)); };
    const std::size_t count = triangles.size() / 3;
    std::vector<Edge> edges;
    edges.reserve(3 * count);
    for (std::size_t t = 0; t < count; ++t)
        for (int e = 0; e < 3; ++e) {
            const glm::vec3 &a = triangles[3 * t + std::size_t(e)], &b = triangles[3 * t + std::size_t((e + 1) % 3)];
            if (!std::isfinite(a.x + a.y + a.z + b.x + b.y + b.z))
                continue;
            Edge edge;
            bits(a, edge.key.data());
            bits(b, edge.key.data() + 3);
            edge.corner = std::uint32_t(3 * t + std::size_t(e));
            edges.push_back(edge);
        }
    std::sort(edges.begin(), edges.end());
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<glm::vec3> opposite(3 * count, glm::vec3(nan));
    for (std::size_t i = 0; i < edges.size(); ++i) {
        const Edge &edge = edges[i];
        if ((i > 0 && edges[i - 1].key == edge.key) || (i + 1 < edges.size() && edges[i + 1].key == edge.key))
            continue;   // the edge itself twice
        Edge reverse;
        std::copy(edge.key.begin() + 3, edge.key.end(), reverse.key.begin());
        std::copy(edge.key.begin(), edge.key.begin() + 3, reverse.key.begin() + 3);
        const auto [from, to] = std::equal_range(edges.begin(), edges.end(), reverse);
        if (to - from != 1)
            continue;   // none, or more than one triangle across
        const std::uint32_t t = from->corner / 3, e = from->corner % 3;
        opposite[edge.corner] = triangles[3 * t + (e + 2) % 3];
    }
    return opposite;
}

}  // namespace occu
