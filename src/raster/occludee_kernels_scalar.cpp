// SPDX-License-Identifier: MIT
// The occludee kernels' scalar twins (occludee_kernels.h): lane by lane,
// the expressions of the AVX2 kernels in the same order.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "raster/occludee_kernels.h"

namespace occu::raster {

void occludee_setup_scalar(OccludeePolygons &p, double width, double height, double depth_margin)
{
    const int n = p.corners;
    p.away = 0;
    for (int l = 0; l < occludee_lanes; ++l) {
        const double grow = p.grow[l];
        double area = 0.0, area_error = 2.0 * n * grow * grow;
        glm::dvec2 lo(1e300), hi(-1e300);
        for (int i = 0; i < n; ++i) {
            const int b = i + 1 < n ? i + 1 : 0, before = i > 0 ? i - 1 : n - 1;
            area += p.x[i][l] * p.y[b][l] - p.x[b][l] * p.y[i][l];
            area_error += grow * (std::abs(p.x[b][l] - p.x[before][l]) + std::abs(p.y[b][l] - p.y[before][l]));
            lo = glm::min(lo, glm::dvec2(p.x[i][l], p.y[i][l]));
            hi = glm::max(hi, glm::dvec2(p.x[i][l], p.y[i][l]));
        }
        p.away |= unsigned(area < -area_error) << l;
        const bool edge_on = area <= area_error;
        glm::dvec2 c[4];
        double z[4];
        for (int i = 0; i < n; ++i) {
            const int from = area < 0.0 ? n - 1 - i : i;
            c[i] = {p.x[from][l], p.y[from][l]};
            z[i] = p.z[from][l];
        }
        p.x_lo[l] = std::max(-1.0, std::floor(lo.x - grow));
        p.y_lo[l] = std::max(-1.0, std::floor(lo.y - grow));
        p.x_hi[l] = std::min(width, std::floor(hi.x + grow));
        p.y_hi[l] = std::min(height, std::floor(hi.y + grow));
        for (int e = 0; e < n; ++e) {
            const glm::dvec2 &a = c[e], &b = c[e + 1 < n ? e + 1 : 0];
            const double ea = a.y - b.y, eb = b.x - a.x;
            p.ea[e][l] = ea;
            p.eb[e][l] = eb;
            p.ec[e][l] = -(ea * a.x + eb * a.y) + std::max(ea, 0.0) + std::max(eb, 0.0) +
                         (std::abs(ea) + std::abs(eb)) * grow;
        }
        const glm::dvec2 u = c[1] - c[0], v = c[2] - c[0];
        const double twice = u.x * v.y - u.y * v.x;
        p.za[l] = 0.0;
        p.zb[l] = 0.0;
        p.zc[l] = p.floor_z[l];
        if (twice > 0.0 && !edge_on) {
            const double du = z[1] - z[0], dv = z[2] - z[0];
            const double za = (du * v.y - dv * u.y) / twice, zb = (dv * u.x - du * v.x) / twice;
            p.za[l] = za;
            p.zb[l] = zb;
            p.zc[l] = z[0] - za * c[0].x - zb * c[0].y + std::min(za, 0.0) + std::min(zb, 0.0) - depth_margin;
        }
    }
}

OccludeeVerdicts occludee_triangles_scalar(const double *matrix, const double *magnitudes, double product_error,
                                           const float *const corners[occludee_lanes][3], double sx, double sy,
                                           double edge_grow, double depth_margin, OccludeePolygons &out)
{
    glm::dmat4 m, magnitude;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            m[c][r] = matrix[4 * c + r];
            magnitude[c][r] = magnitudes[4 * c + r];
        }
    out.corners = 3;
    OccludeeVerdicts verdicts{0, 0};
    for (int l = 0; l < occludee_lanes; ++l) {
        unsigned beyond = 63;
        double window = 0.0, depth = 0.0;
        bool known = true;
        for (int i = 0; i < 3; ++i) {
            const float *corner = corners[l][i];
            const glm::dvec3 p(corner[0], corner[1], corner[2]);
            const glm::dvec4 c = m * glm::dvec4(p, 1.0), b = product_error * (magnitude * glm::dvec4(glm::abs(p), 1.0));
            known = known && std::isfinite(c.x + c.y + c.z + c.w) && c.w > 0.0 && !(c.z < -c.w);
            beyond &= unsigned(c.x > c.w) << 0 | unsigned(c.x < -c.w) << 1 | unsigned(c.y > c.w) << 2 |
                      unsigned(c.y < -c.w) << 3 | unsigned(c.z > c.w) << 4;
            const glm::dvec3 ndc = glm::dvec3(c) / c.w;
            out.x[i][l] = (ndc.x + 1.0) * sx;
            out.y[i][l] = (ndc.y + 1.0) * sy;
            out.z[i][l] = ndc.z * 0.5 + 0.5;
            if (!(c.w > b.w)) {
                window = depth = std::numeric_limits<double>::infinity();
                continue;
            }
            const double w = c.w - b.w;
            window = std::max({window, sx * (b.x + std::abs(ndc.x) * b.w) / w, sy * (b.y + std::abs(ndc.y) * b.w) / w});
            depth = std::max(depth, 0.5 * (b.z + std::abs(ndc.z) * b.w) / w);
        }
        out.floor_z[l] = out.grow[l] = 0.0;   // a lane not set up
        if (!known) {
            verdicts.shows |= 1u << l;
            continue;
        }
        if (beyond) {
            verdicts.skipped |= 1u << l;
            continue;
        }
        // Never nearer than its nearest corner, less the depth margin and
        // what GL's transform may move it by.
        if (!(window < 1e6 && depth < 1.0)) {
            verdicts.shows |= 1u << l;
            continue;
        }
        for (int i = 0; i < 3; ++i)
            out.z[i][l] -= depth;
        out.floor_z[l] = std::min({out.z[0][l], out.z[1][l], out.z[2][l]}) - depth_margin;
        out.grow[l] = edge_grow + window;
    }
    return verdicts;
}

}  // namespace occu::raster
