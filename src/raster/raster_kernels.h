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
// planes has at most 4 + 5 edges.
constexpr int max_edges = 9;
constexpr int tile_size = 8;   // tiles of 8 x 8 depth pixels, 8 lanes per row
constexpr int tile_pixels = tile_size * tile_size;

// A polygon ready for the loops, in depth-pixel coordinates (X, Y integers):
// depth pixel (X, Y) is covered when ea[e] X + (eb[e] Y + ec[e]) >= 0 for
// every edge e (the sample offsets and margins are folded into ec), and its
// depth is then min(za X + (zb Y + zc), zcap).
struct PolygonSetup {
    int edges = 0;
    float ea[max_edges], eb[max_edges], ec[max_edges];
    float inverse_ea[max_edges];   // 1 / ea, 0 where ea is 0: row_span's bounds
    float za = 0.0f, zb = 0.0f, zc = 0.0f, zcap = 1.0f;
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;   // the pixels that may be covered, half-open, inside the buffer
};

struct TileBuffer {
    float *tiles;            // tile by tile, each tile_size rows of tile_size
    std::uint8_t *dirty;     // per tile: written
    int tiles_x;
    int padded_width;        // tiles_x * tile_size
};

// The 8-aligned span of row Y that may hold covered pixels: [*xl, *xr).
// Each edge bounds X from one side; a pixel of slack on each side absorbs
// the reciprocal's rounding (the loops still test every pixel), and the
// bounds are clamped in float before conversion, as a nearly horizontal
// edge gives a huge quotient. Shared by both loops, so both visit the same
// pixels. Internal to each loop's file, and free of library templates: an
// inline function the AVX2 file compiles must not be the one the scalar
// file links to on a CPU without AVX2.
namespace {

// The tile row holding depth pixels x8 .. x8 + 7 of row y (x8 a multiple of 8).
inline float *tile_row(const TileBuffer &b, int x8, int y)
{
    return b.tiles + (std::size_t(y / tile_size) * std::size_t(b.tiles_x) + std::size_t(x8 / tile_size)) * tile_pixels +
           std::size_t(y % tile_size) * tile_size;
}
inline std::uint8_t &tile_dirty(const TileBuffer &b, int x8, int y)
{
    return b.dirty[std::size_t(y / tile_size) * std::size_t(b.tiles_x) + std::size_t(x8 / tile_size)];
}

inline void row_span(const PolygonSetup &s, int y, int padded_width, int *xl, int *xr)
{
    float lo = float(s.x0) - 1.0f, hi = float(s.x1) + 1.0f;
    const float fy = float(y);
    for (int e = 0; e < s.edges; ++e) {
        const float t = s.eb[e] * fy + s.ec[e];
        if (s.ea[e] > 0.0f) {
            const float bound = -t * s.inverse_ea[e] - 1.0f;
            lo = bound > lo ? bound : lo;
        } else if (s.ea[e] < 0.0f) {
            const float bound = -t * s.inverse_ea[e] + 2.0f;
            hi = bound < hi ? bound : hi;
        } else if (t < 0.0f) {
            hi = lo;
        }
    }
    lo = lo > float(s.x0) ? lo : float(s.x0);
    hi = hi < float(s.x1) ? hi : float(s.x1);
    if (!(lo < hi)) {
        *xl = *xr = 0;
        return;
    }
    *xl = (int(std::floor(lo)) / tile_size) * tile_size;
    const int right = int(std::ceil(hi));
    *xr = right < padded_width ? right : padded_width;
}
}  // namespace

void fill_scalar(const PolygonSetup &s, const TileBuffer &buffer);
void fill_avx2(const PolygonSetup &s, const TileBuffer &buffer);

// Whether every pixel of rows [r0, r1) and columns [c0, c1) of one tile is
// nearer than z.
bool tile_behind_scalar(const float *tile, int c0, int c1, int r0, int r1, float z);
bool tile_behind_avx2(const float *tile, int c0, int c1, int r0, int r1, float z);

}  // namespace occu::raster
