// SPDX-License-Identifier: MIT
// A level's brushes as occluders: see brush_occluders.h.
#include "occluders/brush_occluders.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>

#include <polyclipping/clipper.hpp>

#include "scene/level.h"

namespace occu {

namespace {

// Clipper's integer units per Quake unit; a gap narrower than
// `sliver_units` between covering polygons (float rounding of the face
// vertices, which lie on the brushes' sides) counts as covered.
constexpr double clipper_units = 1024.0;
constexpr double sliver_units = 1.0 / 256.0;

ClipperLib::Path clipper_path(const std::vector<glm::dvec2> &points)
{
    ClipperLib::Path path;
    for (const glm::dvec2 &p : points)
        path.emplace_back(ClipperLib::cInt(std::llround(p.x * clipper_units)),
                          ClipperLib::cInt(std::llround(p.y * clipper_units)));
    if (!ClipperLib::Orientation(path))
        ClipperLib::ReversePath(path);
    return path;
}

ClipperLib::Paths clip(ClipperLib::ClipType type, const ClipperLib::Paths &subject, const ClipperLib::Paths &by)
{
    ClipperLib::Clipper clipper;
    clipper.AddPaths(subject, ClipperLib::ptSubject, true);
    clipper.AddPaths(by, ClipperLib::ptClip, true);
    ClipperLib::Paths out;
    clipper.Execute(type, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    return out;
}

// `paths` grown by half a sliver: gaps of float rounding closed.
ClipperLib::Paths grown(const ClipperLib::Paths &paths)
{
    ClipperLib::ClipperOffset grow;
    grow.AddPaths(paths, ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
    ClipperLib::Paths out;
    grow.Execute(out, sliver_units * clipper_units / 2.0);
    return out;
}

// The convex polygon of the plane (normal, distance) inside `planes` (all
// but `skip`), in the plane's two axes other than `axis` (the one its
// normal is most along): a large square in the plane clipped by them.
std::vector<glm::dvec2> section(const std::vector<glm::vec4> &planes, std::size_t skip, const glm::dvec3 &normal,
                                double distance, int axis)
{
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    std::vector<glm::dvec2> poly{{-65536, -65536}, {65536, -65536}, {65536, 65536}, {-65536, 65536}};
    // The plane's point above (x, y): p[axis] = (distance - n_u x - n_v y) / n_axis.
    for (std::size_t o = 0; o < planes.size() && !poly.empty(); ++o) {
        if (o == skip)
            continue;
        const glm::dvec3 m(planes[o]);
        // m . p <= d along the plane: a x + b y <= c.
        const double a = m[u] - m[axis] * normal[u] / normal[axis], b = m[v] - m[axis] * normal[v] / normal[axis],
                     c = double(planes[o].w) - m[axis] * distance / normal[axis];
        std::vector<glm::dvec2> out;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const glm::dvec2 &p = poly[i], &q = poly[(i + 1) % poly.size()];
            const double dp = a * p.x + b * p.y - c, dq = a * q.x + b * q.y - c;
            if (dp <= 0)
                out.push_back(p);
            if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0))
                out.push_back(p + (q - p) * (dp / (dp - dq)));
        }
        poly = std::move(out);
    }
    return poly;
}

double area(const std::vector<glm::dvec2> &poly)
{
    double twice = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i)
        twice += poly[i].x * poly[(i + 1) % poly.size()].y - poly[(i + 1) % poly.size()].x * poly[i].y;
    return std::abs(twice) / 2.0;
}

int dominant_axis(const glm::dvec3 &n)
{
    int a = 0;
    for (int i = 1; i < 3; ++i)
        if (std::abs(n[i]) > std::abs(n[a]))
            a = i;
    return a;
}

}  // namespace

LevelBrushOccluders level_brush_occluders(const Scene &scene)
{
    if (!scene.level)
        throw std::runtime_error("the scene is not a Quake III level (it has no brushes)");
    const std::vector<Level::Brush> &solids = scene.level->opaque_solids;
    const std::vector<Mesh> &meshes = scene.meshes;
    LevelBrushOccluders level;
    // The opaque triangles, by plane (normal to 1/1024, distance to 1/16
    // unit) and in Quake's coordinates.
    auto plane_key = [](const glm::dvec3 &n, double d) {
        return std::array<long, 4>{std::lround(n.x * 1024), std::lround(n.y * 1024), std::lround(n.z * 1024),
                                   std::lround(d * 16)};
    };
    std::map<std::array<long, 4>, std::vector<std::array<glm::dvec3, 3>>> planar;
    for (const Mesh &mesh : meshes) {
        if (!mesh.occluder)
            continue;
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            std::array<glm::dvec3, 3> q;
            for (int k = 0; k < 3; ++k) {
                const glm::dvec3 o(mesh.positions[mesh.indices[t + std::size_t(k)]]);
                q[std::size_t(k)] = glm::dvec3(o.x, -o.z, o.y) / double(quake3_unit_metres);
            }
            const glm::dvec3 c = glm::cross(q[1] - q[0], q[2] - q[0]);
            const double length = glm::length(c);
            if (!(length > 0.0))
                continue;
            planar[plane_key(c / length, glm::dot(c / length, q[0]))].push_back(q);
        }
    }
    // Each side's part the triangles leave uncovered.
    std::vector<std::vector<ClipperLib::Paths>> open(solids.size());
    level.opaque_brushes.resize(solids.size());
    for (std::size_t s = 0; s < solids.size(); ++s) {
        const Level::Brush &solid = solids[s];
        LevelBrushOccluders::OpaqueBrush &brush = level.opaque_brushes[s];
        for (std::size_t k = 0; k < solid.planes.size(); ++k) {
            const glm::dvec3 n(solid.planes[k]);
            const double d = solid.planes[k].w;
            const int a = dominant_axis(n), u = (a + 1) % 3, v = (a + 2) % 3;
            const std::vector<glm::dvec2> poly = section(solid.planes, k, n, d, a);
            ClipperLib::Paths rest;
            if (poly.size() >= 3 && area(poly) > sliver_units * sliver_units) {
                rest = {clipper_path(poly)};
                const auto found = planar.find(plane_key(n, d));
                if (found != planar.end()) {
                    // The plane's triangles over the side's bounds (a floor's
                    // plane holds thousands, across the level).
                    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
                    for (const glm::dvec2 &p : poly) {
                        lo = glm::min(lo, p);
                        hi = glm::max(hi, p);
                    }
                    ClipperLib::Paths triangles;
                    for (const auto &t : found->second) {
                        const glm::dvec2 a2(t[0][u], t[0][v]), b2(t[1][u], t[1][v]), c2(t[2][u], t[2][v]);
                        const glm::dvec2 top = glm::max(a2, glm::max(b2, c2)), bottom = glm::min(a2, glm::min(b2, c2));
                        if (top.x < lo.x || top.y < lo.y || bottom.x > hi.x || bottom.y > hi.y)
                            continue;
                        triangles.push_back(clipper_path({a2, b2, c2}));
                    }
                    if (!triangles.empty())
                        rest = clip(ClipperLib::ctDifference, rest, grown(triangles));
                }
            }
            brush.planes.emplace_back(glm::vec3(n.x, n.z, -n.y), float(d) * quake3_unit_metres);
            brush.drawn.push_back(rest.empty());
            open[s].push_back(std::move(rest));
        }
    }

    // The boxes: six axial sides on the integer grid, at least a unit
    // thick within the one-unit inset.
    for (std::size_t s = 0; s < solids.size(); ++s) {
        const Level::Brush &solid = solids[s];
        bool box = solid.planes.size() == 6;
        for (const glm::vec4 &p : solid.planes)
            box = box && std::abs(p.x) + std::abs(p.y) + std::abs(p.z) == 1.0f && p.w == std::round(p.w);
        if (!box || !glm::all(glm::lessThan(solid.lo + 2.0f, solid.hi)))
            continue;
        LevelBrushOccluders::BoxBrush result;
        result.bounds = Aabb::of(quake3_to_occu(solid.lo + 1.0f), quake3_to_occu(solid.hi - 1.0f));
        result.number = solid.number;
        result.brush = std::int32_t(s);
        bool usable = false;
        for (std::size_t k = 0; k < 6; ++k) {
            const glm::dvec3 n(solid.planes[k]);
            const int a = dominant_axis(n);
            const bool high = n[a] > 0.0;
            // Quake's axis a in occu's (x, z, -y): Quake's y is occu's z reversed.
            const int axis = a == 0 ? 0 : a == 1 ? 2 : 1;
            const std::size_t side = std::size_t(axis * 2 + (high != (a == 1) ? 1 : 0));
            LevelBrushOccluders::BoxBrush::Side &out = result.sides[side];
            if (open[s][k].empty()) {
                out.closed = true;
                usable = true;
                continue;
            }
            // The rest must lie against other opaque brushes: each holding
            // the slab half a unit thick outside it (its sections just
            // outside the side and half a unit out, convex between).
            const double at = solid.planes[k].w * (high ? 1.0 : -1.0), out_sign = high ? 1.0 : -1.0;
            ClipperLib::Paths rest = open[s][k], against;
            for (std::size_t o = 0; o < solids.size() && !rest.empty(); ++o) {
                const Level::Brush &other = solids[o];
                const int u = (a + 1) % 3, v = (a + 2) % 3;
                if (o == s || !(other.lo[a] <= at + out_sign * 0.5 && at + out_sign * 0.5 <= other.hi[a]) ||
                    !(other.lo[a] <= at && at <= other.hi[a]) || !(other.lo[u] < solid.hi[u] && solid.lo[u] < other.hi[u]) ||
                    !(other.lo[v] < solid.hi[v] && solid.lo[v] < other.hi[v]))
                    continue;
                glm::dvec3 axis_normal(0.0);
                axis_normal[a] = 1.0;
                const std::vector<glm::dvec2> near =
                    section(other.planes, other.planes.size(), axis_normal, at + out_sign * 1e-3, a);
                const std::vector<glm::dvec2> far =
                    section(other.planes, other.planes.size(), axis_normal, at + out_sign * 0.5, a);
                if (near.size() < 3 || far.size() < 3)
                    continue;
                const ClipperLib::Paths held =
                    clip(ClipperLib::ctIntersection, {clipper_path(near)}, {clipper_path(far)});
                if (clip(ClipperLib::ctIntersection, rest, held).empty())
                    continue;
                rest = clip(ClipperLib::ctDifference, rest, grown(held));
                out.against.push_back(std::int32_t(o));
            }
            if (rest.empty()) {
                out.closed = true;
                usable = true;
            } else {
                out.against.clear();
            }
        }
        if (usable)
            level.box_brushes.push_back(result);
    }
    return level;
}

}  // namespace occu
