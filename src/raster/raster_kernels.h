// SPDX-License-Identifier: MIT
// The depth rasterizer's inner loops (raster/depth_rasterizer.h), once in
// scalar code and once in AVX2. Both evaluate the same float expressions,
// in the same order and without fused multiply-add (their files build with
// -ffp-contract=off), so their results are equal bit for bit.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace occu::raster {

// A triangle or quad clipped by the near plane and the four guard-band
// planes has at most 4 + 5 edges; a box's silhouette (six corners) clipped
// by the guard band, 6 + 4.
constexpr int max_edges = 10;
// The guard band, in the viewport's half-widths each way from its centre
// (NDC): polygons reaching past it are clipped there. A clipped polygon
// knows no triangle across its edges, so merged coverage leaves its shared
// edges' depth pixels empty: a wall near the eye reaches far past the
// frame, and at 2 most of a level's walls within a few metres were
// clipped and kept a seam along their diagonals. At 16 window coordinates
// stay within 11,000 pixels (1280 wide at divisor 1), where float's
// rounding stays near a thousandth of a pixel; the margins (float_error
// times this extent) take it in.
constexpr double guard_band = 16.0;
constexpr int tile_size = 8;   // tiles of 8 x 8 depth pixels, 8 lanes per row
constexpr int tile_pixels = tile_size * tile_size;

// A polygon ready for the loops, in depth-pixel coordinates (X, Y integers):
// depth pixel (X, Y) is covered when ea[e] X + (eb[e] Y + ec[e]) >= 0 for
// every edge e (the sample offsets and margins are folded into ec), and its
// depth is then min(za X + (zb Y + zc), zcap).
// No member initializers: the AVX2 path keeps a batch of these on the
// stack and fills in every field it uses.
struct PolygonSetup {
    int edges;
    float ea[max_edges], eb[max_edges], ec[max_edges];
    float za, zb, zc, zcap;
    int x0, y0, x1, y1;   // the pixels that may be covered, half-open, inside the buffer
};

struct TileBuffer {
    float *tiles;            // tile by tile, each tile_size rows of tile_size
    std::uint8_t *dirty;     // per tile: written
    // Per tile, a depth no nearer than its farthest pixel (1 when cleared;
    // lowered when a polygon covers the whole tile): a polygon no nearer
    // than it over the tile can write nothing there.
    float *farthest_bound;
    int tiles_x;
};

// Triangles' first steps, eight at a time in AVX2 lanes: transform, the
// clip-plane tests, the back-face test, projection, the bounding box of the
// depth pixels they may cover, and the setup of those that cover some: the
// same float and double expressions in the same order as
// DepthRasterizer::polygon and rasterize take one triangle at a time.
// Most triangles end before the setup (outside the frustum, back faces, or
// covering no depth pixel wholly, as most of a detailed mesh's do); the rest
// come out set up, or, when they need the near plane or the guard band,
// bare, to take the one-at-a-time way.
// Sets up exactly what that way sets up, so the buffer stays the same.
// Clip coordinates are m * (x, y, z, 1) summed as clip_position does
// (depth_rasterizer.cpp): (m0 x + m1 y) + (m2 z + m3).
struct TriangleScreen {
    const float *view_projection;   // column-major 4 x 4, as glm
    float scale_x, scale_y;         // half the buffer's size: window = (ndc + 1) * scale
    int width, height;              // the buffer, depth pixels
    bool per_pixel_depth;
    // rasterize's constants: a depth pixel's first and last sample
    // offsets, the edge margin per unit of edge normal, the coordinate
    // extent and relative float error its margins scale, the depth margin.
    double first, last, edge_margin, extent, float_error, depth_margin;
    // Merged partial coverage: triangles that cover no depth pixel wholly
    // are kept too (their samples may fuse with others'), with their
    // window corners and the bound of GL's transform error at them
    // (DepthRasterizer::add_transform_error's expressions, in double,
    // product_error its relative error of a matrix product).
    bool keep_partial;
    double product_error;
    double error_scale_x, error_scale_y;   // half the buffer's size, in double
    // keep_partial: the buffer's tiles, for DepthRasterizer::
    // behind_everything's test before a triangle's setup (a triangle it
    // drops would change no pixel); each dirty tile's maximum is taken
    // as that test takes it.
    const float *tiles;
    float *tile_max;
    std::uint8_t *dirty;
    int tiles_x;
};

struct ScreenedTriangle {
    std::uint32_t triangle;   // its number in the call
    bool set_up;              // false: it needs clipping
    PolygonSetup setup;
    // keep_partial only: the corners in window coordinates of the buffer
    // and window depth, and the transform error's bound over them.
    float wx[3], wy[3], depth[3];
    double error_window, error_depth;
};

// Writes the triangles among indices[0 .. 3 count) that may cover a depth
// pixel to `out` (room for count), in order; returns how many.
std::size_t screen_triangles_avx2(const TriangleScreen &screen, const float *positions, const std::uint32_t *indices,
                                  std::size_t count, ScreenedTriangle *out);

// Both loops walk the polygon's bounding box tile by tile, each tile being
// 8 x 8 depth pixels (section 7's tiled buffer). Each function and depth
// they evaluate, a X + (b Y + c) in float, is monotone in X and in Y apart
// (float products and sums round monotonically), so its least and largest
// values over a tile's pixels are its values at two of the tile's corners,
// evaluated by the same expression as at every pixel: a tile outside one
// edge at its nearest corner holds no covered pixel, a tile inside every
// edge at its farthest corners is covered wholly and needs no edge test per
// pixel, and a tile whose farthest depth bound is no farther than the
// polygon's nearest depth there takes nothing. Each of these decisions is
// the one the per-pixel tests would make, so the buffer is the same as
// testing every pixel of the box's rows in every tile the box reaches.
// Masked Occlusion Culling (Hasselgren et al.) rejects and accepts whole
// tiles alike; here the test is the pixels' own float expression, so the
// scalar and AVX2 loops need not agree on which tiles they skip.
//
// Internal to each loop's file, and free of library templates: an inline
// function the AVX2 file compiles must not be the one the scalar file links
// to on a CPU without AVX2.
namespace {

// The tile holding depth pixels x8 .. x8 + 7 of rows y8 .. y8 + 7 (x8, y8
// multiples of 8), and its index.
inline std::size_t tile_index(const TileBuffer &b, int x8, int y8)
{
    return std::size_t(y8 / tile_size) * std::size_t(b.tiles_x) + std::size_t(x8 / tile_size);
}
inline float *tile_at(const TileBuffer &b, std::size_t tile) { return b.tiles + tile * tile_pixels; }

// Rows [row0, row1) of one band of tiles (row0 / 8 == (row1 - 1) / 8), and
// each edge's and the depth's row term eb Y + ec (zb Y + zc, as at every
// pixel) at the rows where it is least and largest.
struct Band {
    int y8, row0, row1;
    float least_edge_term[max_edges], largest_edge_term[max_edges];
    float nearest_depth_term, farthest_depth_term;
};

// `edges` is s.edges (a constant where a loop specializes on it).
inline void band_terms(const PolygonSetup &s, int edges, int row0, int row1, Band *band)
{
    band->y8 = row0 / tile_size * tile_size;
    band->row0 = row0;
    band->row1 = row1;
    const float first = float(row0), last = float(row1 - 1);
    for (int e = 0; e < edges; ++e) {
        band->least_edge_term[e] = s.eb[e] * (s.eb[e] > 0.0f ? first : last) + s.ec[e];
        band->largest_edge_term[e] = s.eb[e] * (s.eb[e] > 0.0f ? last : first) + s.ec[e];
    }
    band->nearest_depth_term = s.zb * (s.zb > 0.0f ? first : last) + s.zc;
    band->farthest_depth_term = s.zb * (s.zb > 0.0f ? last : first) + s.zc;
}

enum class Cover { none, part, whole };

// How the polygon covers the band's rows of the tile at columns x8 .. x8 + 7.
inline Cover tile_cover(const PolygonSetup &s, const Band &band, int x8)
{
    const float left = float(x8), right = float(x8 + tile_size - 1);
    bool whole = true;
    for (int e = 0; e < s.edges; ++e) {
        const bool rising = s.ea[e] > 0.0f;
        const float largest = s.ea[e] * (rising ? right : left) + band.largest_edge_term[e];
        if (largest < 0.0f)
            return Cover::none;
        const float least = s.ea[e] * (rising ? left : right) + band.least_edge_term[e];
        whole = whole && least >= 0.0f;   // false for NaN: tested pixel by pixel
    }
    return whole ? Cover::whole : Cover::part;
}

// The polygon's nearest and farthest depth over the band's rows of the
// tile at columns x8 .. x8 + 7, the per-pixel expression at two corners.
inline float tile_nearest_depth(const PolygonSetup &s, const Band &band, int x8)
{
    const float z = s.za * float(s.za > 0.0f ? x8 : x8 + tile_size - 1) + band.nearest_depth_term;
    return s.zcap < z ? s.zcap : z;
}
inline float tile_farthest_depth(const PolygonSetup &s, const Band &band, int x8)
{
    const float z = s.za * float(s.za > 0.0f ? x8 + tile_size - 1 : x8) + band.farthest_depth_term;
    return s.zcap < z ? s.zcap : z;
}

}  // namespace

void fill_scalar(const PolygonSetup &s, const TileBuffer &buffer);
void fill_avx2(const PolygonSetup &s, const TileBuffer &buffer);

// Merged partial coverage (DepthRasterizer::merge_partial): where each
// edge of a polygon crosses each row of samples of a row of depth pixels,
// as the run of sample columns it holds. Sample column c (of depth pixel
// c / k) lies at u = (c + 0.5) / k, sample row j of depth pixel row y at
// v = y + (j + 0.5) / k. A line (an edge's held constant, or its reach
// beyond a shared edge) crosses sample row v at u = start + slope v (in
// double, start = -c / a and slope = -b / a for the edge a u + b v + c >=
// 0); where rising (a > 0) it holds the columns from the crossing on,
// else those up to it.
//
// Each crossing is moved inwards by a bound of its rounding before it
// becomes a column, so that every column in the run has the exact edge
// function at least the line's constant: the rounding of start and slope
// (eps each of |start| and |slope v|), of v (2 eps of |slope v|), of the
// product and the sum (eps each) is within 4 eps of |start| + |slope v| +
// |crossing|, taken twice; the column's own, (crossing +- slack) k - 0.5,
// within 4 eps of it and 1. Every step is one IEEE operation in the same
// order in both loops (no fused multiply-add), so their columns are equal.
//
// An edge along a row (a = 0) holds the whole row or nothing: its line is
// level, with start its constant c and slope its b, and holds the row
// where fl(c + fl(b v)) - 8 eps (|c| + |b v|) >= 0 (v, b v and the sum
// round within 4 eps of those terms, taken twice); it counts as rising,
// from column c_lo or c_hi + 1.
//
// Several rows of depth pixels at once, as Masked Occlusion Culling takes
// a tile's rows (Hasselgren, Andersson and Akenine-Moeller 2016): lane l
// is sample row l mod k of row y + l / k, for the rows_at_once(k) rows
// whose k sample rows fit in eight lanes (one row for k > 4; for k = 3,
// lanes 6 and 7 hold nothing).
inline int rows_at_once(int k) { return 8 / k; }
constexpr int max_lines = max_edges + 3;
struct Crossings {
    int c_lo, c_hi;   // the sample columns of the polygon's box
    int y_end;        // the row past the polygon's box: no lanes for rows from it on
    int k;
    // Lane l's row offset from y (l / k) and sample row offset (((l mod
    // k) + 0.5) / k), as double; any finite value in a lane that holds
    // nothing.
    const double *lane_row, *lane_offset;
    double start[max_lines], slope[max_lines];
    bool rising[max_lines];   // rising (or level)
    bool level[max_lines];
    // The polygon's edges: edge e's held line is line e; for bit e of
    // `candidates` (a triangle across edge e), its reach is line
    // reach_line[e], of the same slope (slope v is shared). Bit e of
    // rising_edges: edge e rises.
    int edges, candidates, reach_line[3];
    unsigned rising_edges;
};

// The rows' runs, from their lines' crossings, lane by lane: per sample
// row, the columns every edge holds (held_lo .. held_hi, empty where lo >
// hi), and for each edge e with a triangle across, those within its reach
// but outside it (its reach less its held run: both end on the same
// side), inside every other edge (band_lo[e] .. band_hi[e]; bit l of
// band_lanes[e]: lane l's band holds a column); and per row, in the lane
// of its first sample row, the columns some run holds, [first, last], and
// those every sample row's held run holds, [whole_first, whole_last].
struct RowsRuns {
    alignas(32) std::int32_t held_lo[8], held_hi[8], band_lo[3][8], band_hi[3][8];
    alignas(32) std::int32_t first[8], last[8], whole_first[8], whole_last[8];
    unsigned band_lanes[3];
};

// For rows y .. y + rows_at_once(k) - 1 below y_end: per line and lane,
// where rising, the first column held, clamped to [c_lo, c_hi + 1] (c_hi
// + 1: none); else the last, clamped to [c_lo - 1, c_hi] (c_lo - 1: none),
// a NaN crossing holding none; then the runs they bound. Returns bit r
// where row y + r has a run holding a column (first <= last), none for
// rows from y_end on, whose lanes are not computed (their contents mean
// nothing).
unsigned partial_rows_runs_scalar(const Crossings &c, int y, RowsRuns &runs);
unsigned partial_rows_runs_avx2(const Crossings &c, int y, RowsRuns &runs);

// The triangle across a shared edge (DepthRasterizer::set_up_across): a
// sample (u, v) is inside it where fl(fl(ea u) + fl(eb v)) >= held for its
// two other edges, and its depth over a depth pixel is depth's (as
// PolygonSetup's), widened by depth_error and rounded up.
struct PartialAcross {
    float ea[2], eb[2], held[2];
    double depth_error;
    PolygonSetup depth;
};

// The partial layer as its rows' walk reads and writes it, tile by tile
// (TileBuffer's layout): each pixel's depth, partial depth and partial
// mask, the mask in two planes of 32 bits (bits 0-31 and 32-63 of the k x
// k samples, bit j k + i sample column i of sample row j); per tile its
// maximum (up to date where not dirty), the fill's bound of its farthest
// depth, and whether a depth (dirty) or a partial mask was written.
struct PartialLayer {
    float *depth, *partial_depth;
    std::uint32_t *mask_lo, *mask_hi;
    const float *tile_max, *farthest_bound;
    std::uint8_t *dirty, *partial_written;
    int tiles_x;
};

// The depth bound partial_next_up(float(double(z) + error)) as one float
// sum, z + add, for every float z in [lo, hi] (lo > hi: for none), so that
// a loop can take it without the round trip through double (the AVX2
// twin of merge_partial_rows, where the bound is most of a tile row's
// latency). In [1/2, 1), where window depths mostly lie, the floats are
// the multiples of u = 2^-24 and the doubles those of 2^-53, z an even one
// of these; so while z + error stays below 1, double(z) + error rounds to
// z + e1, e1 = error rounded to a multiple of 2^-53 as (1/2 + error) - 1/2
// rounds it (ties to even alike). With e1 = (q + f) u, q an integer and 0
// <= f < 1, the float nearest z + e1 is z + q u for f < 1/2 and z + (q +
// 1) u for f > 1/2 (f = 1/2 is a tie, whose side depends on z: no range),
// and the next float up adds u. So for add = (q + 1 + [f > 1/2]) u and z
// in [1/2, 1 - add - u], every step stays in [1/2, 1 - u], the bound is
// z + add, a float, and the float sum z + add is exact.
struct PartialDepthStep {
    float add, lo, hi;
};
inline PartialDepthStep partial_depth_step(double error)
{
    PartialDepthStep step{0.0f, 1.0f, 0.0f};
    if (!(error >= 0.0 && error < 0x1p-8))
        return step;
    const double e1 = (0.5 + error) - 0.5;
    const double units = e1 * 0x1p24;                    // exact: a power of two
    const double q = std::floor(units), f = units - q;   // exact
    if (f == 0.5)
        return step;
    const double add = (q + (f > 0.5 ? 2.0 : 1.0)) * 0x1p-24;   // below 2^-7: exact in float
    step.add = float(add);
    step.lo = 0.5f;
    step.hi = float(1.0 - add - 0x1p-24);   // a multiple of u in [1/2, 1): exact
    return step;
}

// A polygon's merged partial coverage, a row of depth pixels at a time,
// as Masked Occlusion Culling updates a tile row (Hasselgren, Andersson and
// Akenine-Moeller 2016, its triangle rasterization): each tile row the
// row's runs cross, its eight depth pixels x8 .. x8 + 7 in lanes with no
// branch per pixel, one call for the rows, the masks and depths in
// registers from step to step.
//
// A tile row is passed over where every pixel's samples are all held
// between two such pixels (the fill has taken them: its margins are no
// wider than these), or where the tile is nearer everywhere than `behind`
// (DepthRasterizer::behind_everything, tile by tile), by its maximum where
// up to date, or else by the fill's bound. Otherwise each pixel's depth
// bound is min(za X + (zb Y + zc), zcap) widened by depth_error and rounded
// up (partial_next_up), and a pixel no farther than its depth takes nothing
// (the bound only rises). A pixel's mask is its held runs' samples and,
// for each edge with a triangle across whose band holds a sample of a
// farther pixel, that band's samples inside the triangle across; its depth
// bound rises to each such triangle's where that holds one of its samples.
// A pixel with no sample or whose depth is no farther than the bound
// takes nothing; else its mask joins its partial mask and its partial
// depth becomes the farther of the two (its own where the mask was empty),
// and where the joint mask fills, the pixel takes that depth if nearer and
// the partial mask empties.
struct PartialRows {
    int k;
    float offset[8];            // sample offsets within a depth pixel
    std::uint32_t full_lo, full_hi;
    float za, zb, zc, zcap;
    double depth_error;
    PartialDepthStep depth_step;   // partial_depth_step(depth_error), for the AVX2 twin
    float behind;
    // 2^32 / k + 1: sample column c >= 0's depth pixel c / k is c
    // reciprocal >> 32 (DepthRasterizer::merge_partial).
    std::uint64_t reciprocal;
    // Edge e's triangle across (null: none), once bit e of `asked` is set.
    const PartialAcross *across[3];
    unsigned asked;
    // The walk stops where a farther pixel first holds a sample of the
    // band of an edge not asked about yet: it sets `wanted` to that edge
    // and resume_x8 to that tile row, and returns the rows left, for the
    // caller to set the triangle across up (DepthRasterizer::set_up_across)
    // and call again. resume_x8 (0 at first): the tile row the first row
    // left starts from.
    int wanted, resume_x8;
    bool wrote;   // set where a depth changed
};

// Rows y + r for bit r of `found` (partial_rows_runs' rows, each holding a
// column), each in turn. Returns the rows left where it stops for a
// triangle across, else 0.
unsigned merge_partial_rows_scalar(PartialRows &rows, const RowsRuns &runs, int y, unsigned found,
                                   const PartialLayer &layer);
unsigned merge_partial_rows_avx2(PartialRows &rows, const RowsRuns &runs, int y, unsigned found,
                                 const PartialLayer &layer);

// std::nextafter(z, 2.0f), for merged coverage's depth bounds: the next float up (a NaN
// or infinity stays; -0 becomes the least positive float, as 0 does).
inline float partial_next_up(float z)
{
    z += 0.0f;
    if (!(z == z) || z == __builtin_inff())
        return z;
    std::uint32_t bits;
    __builtin_memcpy(&bits, &z, sizeof bits);
    bits = z < 0.0f ? bits - 1 : bits + 1;
    __builtin_memcpy(&z, &bits, sizeof z);
    return z;
}

// Whether every pixel of rows [r0, r1) and columns [c0, c1) of one tile is
// nearer than z.
bool tile_behind_scalar(const float *tile, int c0, int c1, int r0, int r1, float z);
bool tile_behind_avx2(const float *tile, int c0, int c1, int r0, int r1, float z);

}  // namespace occu::raster
