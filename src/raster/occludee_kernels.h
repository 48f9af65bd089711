// SPDX-License-Identifier: MIT
// The occludee test's inner loops (DepthRasterizer::triangles_occluded and
// polygon_behind): a triangle's corners transformed with the bound of GL's
// error, and a polygon's reach and nearest depth over the depth pixels of
// one tile, tested against their depths. The scalar loops live in
// depth_rasterizer.cpp; these AVX2 ones take a corner's four rows, or four
// depth pixels of a tile row, at once, with the same double expressions in
// the same order and no fused multiply-add (the file builds with
// -ffp-contract=off), so the two answer alike.
#pragma once

namespace occu::raster {

// A triangle's corners (positions, xyz floats each), one a lane, through a
// view-projection matrix given as double columns m0..m3, glm's order
// (m0 x + m1 y) + (m2 z + m3), with the bound b of GL's float error in each
// clip coordinate, product_error ((|m0| |x| + |m1| |y|) + (|m2| |z| + |m3|))
// with the matrix's magnitudes `magnitude`. Out: each corner in window
// coordinates of the buffer ((x / w + 1) sx, (y / w + 1) sy) and window
// depth z / w 0.5 + 0.5; `beyond`, bit s set where every corner lies beyond
// side s (x > w, x < -w, y > w, y < -w, z > w); and how far GL's transform
// may move the triangle, the largest over the corners of
// sx (b.x + |x / w| b.w) / (w - b.w) and sy's twin (`window`) and
// 0.5 (b.z + |z / w| b.w) / (w - b.w) (`depth`), both infinite where a
// corner has w <= b.w. False (the rest then unset) where a corner is not
// finite, has !(w > 0) or z < -w.
struct OccludeeCorners {
    double x[4], y[4], z[4];   // lanes 0-2
    unsigned beyond;
    double window, depth;
};
bool occludee_corners_avx2(const double *m, const double *magnitude, double product_error,
                           const float *const corners[3], double sx, double sy, OccludeeCorners &out);
// Its scalar twin (raster_kernels_scalar.cpp): the same expressions in the
// same order, corner by corner.
bool occludee_corners_scalar(const double *m, const double *magnitude, double product_error,
                             const float *const corners[3], double sx, double sy, OccludeeCorners &out);

// A box's eight corners (Aabb::corner's order: bit 0 max x, bit 1 max y,
// bit 2 max z; lo and hi its min and max) through the view-projection matrix
// as double columns m0..m3, glm's order, each corner a lane: window
// coordinates of the buffer ((x / w + 1) sx, (y / w + 1) sy) and window
// depth (z / w 0.5 + 0.5). False (the outputs then unset) where a corner
// has !(w > 0) or z < -w: in front of the near plane, or around the eye.
bool box_corners_window_avx2(const double *m, const float lo[3], const float hi[3], double sx, double sy,
                             double window_x[8], double window_y[8], double depth[8]);

// A convex polygon of at most 4 edges in buffer pixels: depth pixel (X, Y)
// is reached where (ea[e] X + eb[e] Y) + ec[e] >= 0 for every edge e, and
// the polygon is no nearer there than max(floor_z, (za X + zb Y) + zc).
struct OccludeeEdges {
    int edges;
    double ea[4], eb[4], ec[4];
    double za, zb, zc, floor_z;
};

// Whether every depth pixel of rows [r0, r1) and columns [c0, c1) of `tile`
// (tile-relative; the tile's lower left depth pixel is (x8, y8)) that the
// polygon reaches is nearer than the polygon there; false at the first
// that is not, or holds NaN.
bool tile_pixels_behind_avx2(const OccludeeEdges &p, const float *tile, int x8, int y8, int c0, int c1, int r0,
                             int r1);

}  // namespace occu::raster
