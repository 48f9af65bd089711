// SPDX-License-Identifier: MIT
// The occludee test's inner loop (DepthRasterizer::polygon_behind): a
// polygon's reach and nearest depth over the depth pixels of one tile,
// tested against their depths. The scalar loop lives in polygon_behind;
// this AVX2 one takes four depth pixels of a tile row at once with the same
// double expressions in the same order, no fused multiply-add (the file
// builds with -ffp-contract=off), so the two answer alike.
#pragma once

namespace occu::raster {

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
