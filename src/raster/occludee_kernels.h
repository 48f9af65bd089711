// SPDX-License-Identifier: MIT
// The occludee test's inner loops (DepthRasterizer::first_shown,
// faces_occluded and polygon_behind), four polygons at a time, one a lane,
// as Masked Occlusion Culling sets up its triangles in lanes before walking
// them one by one: triangles' corners transformed with the bound of GL's
// error; polygons' facing, reach, edge functions and depth plane; and one
// polygon's tiles and pixels tested against their depths (whose scalar
// twin is DepthRasterizer::polygon_behind's own walk). The AVX2 kernels
// (occludee_kernels_avx2.cpp) take a double lane where the scalar twins
// (occludee_kernels_scalar.cpp) loop over the lanes, with the same double
// expressions in the same order and no fused multiply-add (both files build
// with -ffp-contract=off), so the two are equal bit for bit.
#pragma once

namespace occu::raster {

constexpr int occludee_lanes = 4;

// Up to four convex polygons of `corners` (3 or 4) corners each, one a lane,
// as the occludee test sees them. In: corner i of lane l at (x[i][l],
// y[i][l]) in window coordinates of the buffer (depth pixels), window depth
// z[i][l]; the polygon no nearer anywhere than floor_z[l]; GL may put each
// corner up to grow[l] buffer pixels from ours either way. Out
// (occludee_setup_*): the polygon as DepthRasterizer::polygon_behind walks
// it, depth pixel (X, Y) reached where (ea[e][l] X + eb[e][l] Y) + ec[e][l]
// >= 0 for every edge e, and no nearer there than max(floor_z[l], (za[l] X +
// zb[l] Y) + zc[l]).
struct OccludeePolygons {
    int corners;
    double x[4][occludee_lanes], y[4][occludee_lanes], z[4][occludee_lanes];
    double floor_z[occludee_lanes], grow[occludee_lanes];

    unsigned away;   // bit l: faces away by more than moving its corners by grow[l] can change; GL culls it
    // The depth pixels whose square it may reach: floor(lowest corner -
    // grow) .. floor(highest corner + grow), the low ends raised to -1, the
    // high ends lowered to the buffer's size.
    double x_lo[occludee_lanes], y_lo[occludee_lanes], x_hi[occludee_lanes], y_hi[occludee_lanes];
    double ea[4][occludee_lanes], eb[4][occludee_lanes], ec[4][occludee_lanes];   // [edge][lane]
    double za[occludee_lanes], zb[occludee_lanes], zc[occludee_lanes];
};

// Sets up every lane of `p` (lanes nobody reads included; the inputs there
// must only be set): twice the signed area and how much moving each corner
// by grow can change it (its derivative by corner i is the perpendicular of
// the diagonal between i's neighbours, and the products of two moves add at
// most 2 n grow^2); facing away below minus that; a polygon within it of
// edge-on faces whichever way GL's rounded corners say, so it is taken
// counter-clockwise (its corners reversed where the area is negative) and
// at floor_z throughout, its plane being as uncertain as its facing. The
// edges outward, each at the corner of a pixel's square on its inside
// (the largest E over the square) less grow times its normal's 1-norm; the
// plane through corners 0-2, its smallest value over a pixel's square, less
// depth_margin. `width` and `height` are the buffer's, in depth pixels.
void occludee_setup_avx2(OccludeePolygons &p, double width, double height, double depth_margin);
void occludee_setup_scalar(OccludeePolygons &p, double width, double height, double depth_margin);

// Four triangles' corners (triangle l's corner i at corners[l][i], xyz
// floats each), one triangle a lane, through a view-projection matrix given
// as double columns m0..m3, glm's order (m0 x + m1 y) + (m2 z + m3), with
// the bound b of GL's float error in each clip coordinate, product_error
// ((|m0| |x| + |m1| |y|) + (|m2| |z| + |m3|)) with the matrix's magnitudes
// `magnitude`. Each corner goes to window coordinates of the buffer ((x /
// w + 1) sx, (y / w + 1) sy) and window depth z / w 0.5 + 0.5. How far GL's
// transform may move a triangle is the largest over its corners of sx (b.x
// + |x / w| b.w) / (w - b.w) and sy's twin (`window`) and 0.5 (b.z + |z /
// w| b.w) / (w - b.w) (`depth`), infinite where a corner has w <= b.w.
// Per lane, in this order: `shows` where a corner is not finite, has !(w >
// 0) or z < -w (across the near plane, around the eye or unknown: never
// taken as hidden); else `skipped` where every corner lies beyond one side
// (x > w, x < -w, y > w, y < -w or z > w: GL draws none of it); else
// `shows` where window >= 1e6 or depth >= 1; else it is set up in `out`'s
// inputs: its corners, each depth less `depth`, floor_z the least of those
// less depth_margin, grow edge_grow + window. out.corners is set to 3.
struct OccludeeVerdicts {
    unsigned shows, skipped;   // bit l for lane l
};
OccludeeVerdicts occludee_triangles_avx2(const double *m, const double *magnitude, double product_error,
                                         const float *const corners[occludee_lanes][3], double sx, double sy,
                                         double edge_grow, double depth_margin, OccludeePolygons &out);
OccludeeVerdicts occludee_triangles_scalar(const double *m, const double *magnitude, double product_error,
                                           const float *const corners[occludee_lanes][3], double sx, double sy,
                                           double edge_grow, double depth_margin, OccludeePolygons &out);

// One triangle's corners as lanes (lane 3 repeats corner 2), the rest as
// occludee_triangles_avx2 with every lane holding that triangle: a lone
// triangle in one pass instead of three. Its scalar twin is
// occludee_triangles_scalar with the triangle in every lane.
OccludeeVerdicts occludee_triangle_avx2(const double *m, const double *magnitude, double product_error,
                                        const float *const corners[3], double sx, double sy, double edge_grow,
                                        double depth_margin, OccludeePolygons &out);

// A box's eight corners (Aabb::corner's order: bit 0 max x, bit 1 max y,
// bit 2 max z; lo and hi its min and max) through the view-projection matrix
// as double columns m0..m3, glm's order, each corner a lane: window
// coordinates of the buffer ((x / w + 1) sx, (y / w + 1) sy) and window
// depth (z / w 0.5 + 0.5). False (the outputs then unset) where a corner
// has !(w > 0) or z < -w: in front of the near plane, or around the eye.
bool box_corners_window_avx2(const double *m, const float lo[3], const float hi[3], double sx, double sy,
                             double window_x[8], double window_y[8], double depth[8]);

// DepthRasterizer::polygon_behind's walk for the depth pixels [x0, x1) x
// [y0, y1) (inside the buffer, not empty) in AVX2: whether every one that
// lane `lane` of `p` (set up, 3 or 4 corners) reaches is nearer than the
// polygon there; false at the first that is not, or holds NaN. `tiles`
// holds the buffer tile by tile (8 rows of 8 pixels each, tiles_x tiles a
// row), `tile_max` each tile's farthest depth: a tile farther nowhere than
// the polygon's nearest over it is settled at once, the scalar walk's
// double expression. Its pixels four a step, in double lanes, with the
// scalar walk's expressions.
bool polygon_behind_avx2(const OccludeePolygons &p, int lane, const float *tiles, const float *tile_max, int tiles_x,
                         int x0, int y0, int x1, int y1);

}  // namespace occu::raster
