// The scalar loops: the reference the AVX2 loops must equal bit for bit.
#include "raster/raster_kernels.h"

namespace occu::raster {

void fill_scalar(const PolygonSetup &s, const TileBuffer &buffer)
{
    float row_term[max_edges];
    for (int y = s.y0; y < s.y1; ++y) {
        int xl, xr;
        row_span(s, y, buffer.padded_width, &xl, &xr);
        if (xl >= xr)
            continue;
        const float fy = float(y);
        for (int e = 0; e < s.edges; ++e)
            row_term[e] = s.eb[e] * fy + s.ec[e];
        const float z_row = s.zb * fy + s.zc;
        for (int x8 = xl; x8 < xr; x8 += tile_size) {
            float *row = tile_row(buffer, x8, y);
            bool wrote = false;
            for (int lane = 0; lane < tile_size; ++lane) {
                const float fx = float(x8 + lane);
                bool inside = true;
                for (int e = 0; e < s.edges; ++e)
                    inside &= s.ea[e] * fx + row_term[e] >= 0.0f;
                const float z = std::min(s.za * fx + z_row, s.zcap);
                if (inside && z < row[lane]) {
                    row[lane] = z;
                    wrote = true;
                }
            }
            if (wrote)
                tile_dirty(buffer, x8, y) = 1;
        }
    }
}

bool tile_behind_scalar(const float *tile, int c0, int c1, int r0, int r1, float z)
{
    for (int r = r0; r < r1; ++r)
        for (int c = c0; c < c1; ++c)
            if (!(tile[r * tile_size + c] < z))
                return false;
    return true;
}

}  // namespace occu::raster
