// SPDX-License-Identifier: MIT
// A CPU depth rasterizer for occluders, in the manner of Leone et al.,
// "Implementing Software Occlusion Culling for Real-Time Applications":
// occluder triangles and quads (quads natively, section 7) go into a
// downscaled, tiled depth buffer (section 7: a quarter of the frame's
// pixels by default), and an occludee is a screen rectangle with one depth,
// its nearest, tested with an early out (section 6).
//
// Conventions (the Culler's, culling/culler.h): positions are world space;
// the view-projection matrix is OpenGL's (clip z in [-w, w]); window depth
// is in [0, 1], 0 nearest, and the cleared buffer holds 1 (nothing). Front
// faces wind counter-clockwise on screen, as GL's default, and back faces
// are skipped (the frame is drawn with back-face culling, so a back face
// hides nothing there). The buffer has ceil(W / k) x ceil(H / k) depth
// pixels for a frame of W x H pixels and a divisor k; depth pixel (X, Y)
// holds the frame pixels [kX, kX + k) x [kY, kY + k), (0, 0) lower left.
//
// Conservative by construction, against the frame GL draws at full
// resolution: a depth pixel is covered by a polygon only when the polygon
// holds the centres of all k x k frame pixels in it (the samples GL's
// rasterization uses), less a margin for GL's subpixel snapping and float
// rounding; its depth is then the polygon's farthest depth over those
// samples, never nearer than GL's depth at any of them. A polygon that
// covers no depth pixel wholly leaves the buffer alone: occluders fuse in
// the buffer (section 3), not within a depth pixel.
//
// Clipping (section 5): polygons are clipped against the near plane only
// where they cross it, so that no vertex has w <= 0; those reaching far
// outside the viewport are also clipped to a guard band (raster::guard_band
// viewports each way) to keep edge functions in float's exact range. Both
// clips keep the polygon convex and inside the original.
//
// Two depth rules (section 5): per-pixel depth (the plane of the polygon),
// or one depth per polygon, its farthest vertex: the paper's "optimal
// choice" for speed, more conservative where a polygon spans much depth.
//
// Optionally (Options::merge_partial_coverage) polygons also fuse within
// a depth pixel, as in Masked Occlusion Culling (Hasselgren, Andersson and
// Akenine-Moeller 2016): each depth pixel keeps, beside its depth, a mask
// of the k x k samples that polygons not covering it wholly hold (by the
// same margins) and the farthest of those polygons' depths over the pixel.
// When the mask fills, every sample is held by a polygon no farther than
// that depth, so the pixel takes it (the nearer of it and its own). Two
// triangles sharing an edge then cover the pixels along it, which neither
// covers alone: without it a mesh of many triangles leaves a seam of empty
// depth pixels along every edge, and an occludee across a seam is never
// hidden. A sample within the edge margin of an edge is held by neither
// triangle's own test; where the caller names the triangle across that
// edge (render_triangles' `across`), the sample is held all the same,
// with the farther of the two triangles' depths: GL's rasterization is
// watertight, so it draws such a sample with one of the two, whichever
// side of its own snapped edge the sample lies (when both face the eye
// with room to spare, lie between the near and far planes, and hold the
// sample inside their other edges by the margin). Without it a seam
// through a sample's margin leaves that depth pixel empty, and an
// occludee across it shown. Far from the origin GL's float transform may
// move a vertex by more than the edge margin (pixels at 1e6 m): merged
// coverage and the triangle test widen their margins by a bound of that
// error (TransformError), and give up where it reaches a pixel. The AVX2
// path screens and sets up triangles eight at a time in this mode too,
// keeping those that cover no depth pixel wholly, with the same float and
// double expressions (the transform error's bound included) as the one
// at a time way. A polygon's partial coverage of a row of depth pixels is
// found as Masked Occlusion Culling finds a span's: each edge's crossing
// point along each row of samples bounds the run of samples it holds, and
// the runs, met across the edges and shifted into each pixel's mask, give
// the samples held (merge_partial), with no sample tested alone; the
// eight depth pixels of a tile row then take their masks, the triangles
// across and the merge rule at once, in lanes, with no branch per pixel
// (raster::merge_partial_rows, scalar and AVX2 twins equal bit for bit).
//
// The inner loops exist twice, scalar and AVX2 (chosen at run time, or by
// the caller); both evaluate the same float expressions in the same order,
// with no fused multiply-add, so their buffers are equal bit for bit. The
// AVX2 path also takes triangles through transform, the clip and back-face
// tests, projection and setup eight at a time, with the same float and
// double expressions as the one-at-a-time way, which quads, boxes and
// triangles that need clipping take.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "geometry/aabb.h"
#include "geometry/pixel_rect.h"
#include "memory/large_buffers.h"

namespace occu {

namespace raster {
struct PolygonSetup;
struct OccludeePolygons;
}

class DepthRasterizer {
public:
    enum class Isa { scalar, avx2 };
    static bool avx2_supported();
    static Isa best_isa() { return avx2_supported() ? Isa::avx2 : Isa::scalar; }

    struct Options {
        int divisor = 2;                 // frame pixels per depth pixel, each way
        bool per_pixel_depth = true;     // false: one farthest depth per polygon
        // Fuse partial coverage within a depth pixel (above); needs
        // divisor <= 8 (a mask of at most 64 samples).
        bool merge_partial_coverage = false;
    };

    // Throws std::invalid_argument for Isa::avx2 on a CPU without it.
    explicit DepthRasterizer(Isa isa = best_isa());

    // Starts a frame: sizes the buffer for a frame of frame_width x
    // frame_height pixels (storage is kept between frames) and clears it.
    // Throws std::invalid_argument for a size or divisor below 1, or a
    // divisor above 8 with merge_partial_coverage.
    void begin(const glm::mat4 &view_projection, int frame_width, int frame_height, const Options &options);

    // Triangles: three indices into `positions` each. Quads: four, a
    // planar convex polygon, counter-clockwise from its front. With merged
    // partial coverage, `across` (3 per triangle, or null) may name for
    // edge e of triangle t (its vertex e to vertex e + 1) the third vertex
    // of the triangle GL draws across that edge (shared_edge_opposites),
    // or hold NaN where there is none.
    void render_triangles(const glm::vec3 *positions, const std::uint32_t *indices, std::size_t triangle_count,
                          const glm::vec3 *across = nullptr);
    void render_quads(const glm::vec3 *positions, const std::uint32_t *indices, std::size_t quad_count);
    // The faces of `box` that face the eye, as quads (Leone, section 5).
    void render_box(const Aabb &box);

    // Keeps, pixel by pixel, the nearer of this buffer and `other` (begun
    // for the same frame and options): occluders rasterized on another
    // thread into a buffer of its own join this one; with merged partial
    // coverage the two masks join too (a pixel whose joint mask fills
    // takes the farther of the two depths). Throws std::invalid_argument
    // when the sizes or the coverage rule differ.
    void merge_nearest(const DepthRasterizer &other);

    // Whether every depth pixel under `frame_rect` (frame pixels, clamped
    // to the frame) is nearer than `z`: an occludee whose nearest window
    // depth is z is then hidden (section 6). Stops at the first depth
    // pixel that is not. An empty rectangle is occluded (it has no pixel).
    bool occluded(const PixelRect &frame_rect, float z) const;

    // Whether every depth pixel `box`'s faces can touch is nearer than the
    // box there: the rectangle test first (its nearest depth over its
    // footprint), and where that fails, the faces that face the eye,
    // rasterized outward (every depth pixel whose square they reach, less
    // nothing) with their nearest depth over each pixel, no nearer bound
    // than the box's nearest corner. Tighter than the rectangle: the
    // pixels of the rectangle's corners outside the box's silhouette, and
    // the depth of the box's far parts, no longer count. False when the
    // box reaches in front of the near plane or holds the eye.
    bool occluded(const Aabb &box, const PixelRect &frame_rect, float z_near) const;
    // The second step alone, for a caller that has tested the rectangle
    // already (or an equivalent, such as a Z-pyramid of this buffer).
    bool faces_occluded(const Aabb &box, float z_near) const;
    // A triangle by its three corners.
    using TriangleCorners = std::array<const glm::vec3 *, 3>;
    // The first of `count` triangles that is not hidden, `count` when all
    // are; a triangle that may face the eye is hidden as faces_occluded
    // hides a box's faces: every depth pixel whose square it reaches
    // nearer than its nearest depth there (and than its nearest corner).
    // Only a triangle that faces away by more than GL's rounding of its
    // corners can change is left out (GL culls it); one nearly edge-on
    // faces whichever way GL's rounded corners say, and is tested. Tighter
    // than the box of the triangles: a leaf tested by what it draws. A
    // triangle reaching in front of the near plane is not hidden. The
    // triangles are set up four at a time in lanes, then walked in order
    // up to the first that shows.
    std::size_t first_shown(const TriangleCorners *triangles, std::size_t count) const;

    int width() const { return width_; }
    int height() const { return height_; }
    int divisor() const { return options_.divisor; }
    Isa isa() const { return isa_; }
    float depth(int x, int y) const;
    // The buffer row by row, (0, 0) lower left: for pyramids and pictures.
    void read(std::vector<float> &depth) const;

    struct Stats {
        std::uint64_t polygons = 0;      // submitted (triangles and quads)
        std::uint64_t rasterized = 0;    // that covered at least one depth pixel's bounding box
        std::uint64_t clipped = 0;       // that needed the near plane or the guard band
    };
    const Stats &stats() const { return stats_; }

private:
    void render_triangles_avx2(const glm::vec3 *positions, const std::uint32_t *indices, std::size_t triangle_count,
                               const glm::vec3 *across);
    // How far GL's float transform of a point may put it from where we
    // compute it, in buffer pixels and window depth: far from the origin
    // (a scene at 1e6 m) a vertex rounds by pixels, far above the edge
    // margin. Bounded by the float error of the matrix products,
    // eps-multiples of the sum of the products' absolute terms.
    struct TransformError {
        double window, depth;   // {} is none
    };
    TransformError transform_error(const glm::vec3 *points, int count) const;
    // Widens `e` by the bound for point p, whose clip position c = m p.
    void add_transform_error(const glm::dmat4 &m, const glm::dvec3 &p, const glm::dvec4 &c, TransformError &e) const;

    void polygon(const glm::vec4 *clip, int count, const glm::vec3 *across = nullptr, TransformError error = {});
    // A box's silhouette from its eight corners' clip positions, at its
    // farthest corner's depth, where no corner needs clipping (render_box).
    void silhouette(const glm::vec4 *corners);
    void rasterize(const glm::vec2 *window, const float *depth, int count, const glm::vec3 *across = nullptr,
                   TransformError error = {});
    // Merged coverage: whether every depth pixel the polygon (or a sample
    // beyond its edges) may reach is nearer than its nearest corner.
    bool behind_everything(const glm::vec2 *window, const float *depth, int n) const;
    // A polygon set up: its whole depth pixels, and its partial coverage.
    void draw(const glm::vec2 *window, const float *depth, int n, const raster::PolygonSetup &setup,
              const glm::vec3 *across, TransformError error);
    void merge_partial(const glm::vec2 *window, const float *depth, int count, const raster::PolygonSetup &setup,
                       const glm::vec3 *across, TransformError error);
    // merge_partial's parts: the polygon's edges at sample precision and
    // the depth pixels they may reach; the triangle across edge e, set up
    // on first need (false where it cannot count) by set_up_neighbour.
    struct PartialEdges;
    PartialEdges partial_edges(const glm::vec2 *window, const float *depth, int count, const glm::vec3 *across,
                               TransformError error) const;
    bool set_up_across(PartialEdges &edges, int e) const;
    bool set_up_neighbour(PartialEdges &edges, int e) const;
    // Adds sample mask `mask` held no farther than z to the pixel at
    // `index` (tile layout), as raster::merge_partial_rows' rule does
    // (merge_nearest: another buffer's layer); returns whether its depth
    // changed.
    bool add_partial(std::size_t index, std::uint64_t mask, float z);
    void update_tile_maxima() const;
    void refresh_tile_maximum(std::size_t tile) const;   // tile_max_ from its pixels; no longer dirty
    // Whether every depth pixel of [x0, x1) x [y0, y1) (buffer pixels,
    // inside the buffer, not empty) is nearer than z, by the tiles'
    // maxima; brings those tiles' maxima up to date.
    bool all_nearer(int x0, int y0, int x1, int y1, float z) const;
    // Whether every depth pixel whose square lane `lane` of `p` (set up by
    // raster::occludee_setup_*, not facing away) reaches is nearer than the
    // polygon there, and than its floor_z: its reach tile by tile, a tile
    // whose farthest depth is nearer than the polygon's nearest over it
    // settled at once.
    bool polygon_behind(const raster::OccludeePolygons &p, int lane) const;
    void occludee_setup(raster::OccludeePolygons &p) const;   // the ISA's kernel

    Isa isa_;
    Options options_;
    glm::mat4 view_projection_{1.0f};
    glm::dmat4 view_projection_double_{1.0};      // the same in double, and its entries' magnitudes:
    glm::dmat4 view_projection_magnitude_{1.0};   // the occludee test's transform and its error bound
    int frame_width_ = 0, frame_height_ = 0;
    int width_ = 0, height_ = 0;    // depth pixels
    int tiles_x_ = 0, tiles_y_ = 0;  // 8 x 8 tiles
    // The depth buffer and the partial layer: rows of 8 loaded and stored
    // whole, in cache-line-aligned storage (memory/large_buffers.h).
    LargeBuffer<float> tiles_;                   // tile by tile, each 8 rows of 8
    mutable std::vector<float> tile_max_;        // farthest depth per tile
    std::vector<float> farthest_bound_;          // per tile, no nearer than its farthest depth (raster::TileBuffer)
    mutable std::vector<std::uint8_t> dirty_;    // tile written since its maximum was taken
    mutable bool any_dirty_ = false;
    // merge_partial_coverage: per depth pixel (the tiles' layout), the
    // samples held by polygons not covering it wholly, and their farthest
    // depth; empty otherwise.
    // The masks in two planes, bits 0-31 and 32-63 (raster::PartialLayer).
    LargeBuffer<std::uint32_t> partial_mask_lo_, partial_mask_hi_;
    std::uint64_t partial_mask(std::size_t index) const
    {
        return std::uint64_t(partial_mask_hi_[index]) << 32 | partial_mask_lo_[index];
    }
    LargeBuffer<float> partial_depth_;
    std::vector<std::uint8_t> partial_written_;   // per tile: a mask set since begin
    std::uint64_t full_mask_ = 0;
    double lane_row_[8] = {}, lane_offset_[8] = {};   // raster::Crossings' for the divisor
    float sample_offset_[8] = {};                      // lane_offset_[0 .. k - 1] as float
    Stats stats_;
};

// For each edge of each triangle (triangles[t][e] to triangles[t][e + 1]),
// the third corner of the one triangle that has the same edge the other
// way round, its corners equal bit for bit (GL transforms equal positions
// alike, so the two share the edge exactly); NaN where no triangle or more
// than one does, or where the edge itself is not unique. 3 per triangle.
std::vector<glm::vec3> shared_edge_opposites(const std::vector<glm::vec3> &triangles);

}  // namespace occu
