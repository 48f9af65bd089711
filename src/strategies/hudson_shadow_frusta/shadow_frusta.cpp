// SPDX-License-Identifier: MIT
// Hudson et al.'s shadow frusta (Moeller and Haines, "Occlusion Culling
// Algorithms", section "Shadow Culling"): see shadow_frusta.h for the
// statements and their proofs.
#include "strategies/hudson_shadow_frusta/shadow_frusta.h"

#include <algorithm>
#include <tuple>

namespace occu {

namespace {

glm::dvec3 lo(const Aabb &b) { return glm::dvec3(b.min); }
glm::dvec3 hi(const Aabb &b) { return glm::dvec3(b.max); }

}  // namespace

std::optional<ConvexRegion> polygon_shadow(const glm::dvec3 &eye, const std::vector<glm::dvec3> &polygon)
{
    const double margin = shadow_margin(std::max(magnitude(eye), polygon_magnitude(polygon)));
    const auto facts = polygon_facts(polygon, margin);
    if (!facts)
        return std::nullopt;
    // The eye's side of the polygon is its front; the eye must be clear of
    // the plane (on it, the "frustum" has no inside).
    glm::dvec3 front = facts->normal;
    auto [near, far] = extent_along(polygon, front);
    double eye_height = glm::dot(front, eye);
    if (eye_height < near) {
        front = -front;
        std::tie(near, far) = std::make_pair(-far, -near);
        eye_height = -eye_height;
    }
    if (!(eye_height - far > margin))
        return std::nullopt;
    ConvexRegion r;
    r.margin = margin;
    // The near plane: beyond every vertex (Hudson's "plane in which the
    // occluder lies").
    r.add(HalfSpace{-front, near});
    // A side plane per edge, through the eye: cross(edge, start - eye),
    // whose sign follows the winding; taken towards the polygon's inside.
    const double winding = glm::dot(facts->normal, front) > 0.0 ? 1.0 : -1.0;
    glm::dvec3 centre(0.0);
    for (const glm::dvec3 &v : polygon)
        centre += v;
    centre /= double(polygon.size());
    for (const auto &[a, b] : facts->edges) {
        const auto side = plane_through(eye, winding * glm::cross(b - a, a - eye));
        // The polygon's centre must lie well inside every side plane, or
        // the polygon is too thin to trust the planes' orientation.
        if (!side || !(side->distance(centre) > margin) || r.count == int(r.planes.size()))
            return std::nullopt;   // (or more edges than a region holds: not an occluder of ours)
        r.add(*side);
    }
    return r;
}

std::optional<ConvexRegion> box_shadow(const glm::dvec3 &eye, const Aabb &occluder)
{
    const double margin = shadow_margin(std::max(magnitude(eye), magnitude(occluder)));
    for (int a = 0; a < 3; ++a)
        if (!(double(occluder.max[a]) - double(occluder.min[a]) > margin))
            return std::nullopt;
    const auto front = front_faces(eye, occluder, margin);
    if (!front)
        return std::nullopt;
    ConvexRegion r;
    r.margin = margin;
    // Beyond the plane of every face the eye sees (the near surface).
    for (int f = 0; f < 6; ++f)
        if (*front & (1u << f)) {
            const glm::dvec3 n = box_face_normal(f);
            const double plane = f % 2 ? double(occluder.max[f / 2]) : double(occluder.min[f / 2]);
            r.add(HalfSpace{-n, plane * n[f / 2]});
        }
    // The cone over the silhouette: the edges between a face the eye sees
    // and one it does not, each with the eye spanning a side plane that has
    // the box inside.
    const glm::dvec3 centre = 0.5 * (lo(occluder) + hi(occluder));
    for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        for (int si = 0; si < 2; ++si)
            for (int sj = 0; sj < 2; ++sj) {
                const bool fi = *front & (1u << (2 * i + si)), fj = *front & (1u << (2 * j + sj));
                if (fi == fj)
                    continue;
                glm::dvec3 p0(0.0);
                p0[i] = si ? occluder.max[i] : occluder.min[i];
                p0[j] = sj ? occluder.max[j] : occluder.min[j];
                p0[k] = occluder.min[k];
                glm::dvec3 p1 = p0;
                p1[k] = occluder.max[k];
                auto side = plane_through(eye, glm::cross(p1 - p0, p0 - eye));
                if (!side)
                    return std::nullopt;
                if (side->distance(centre) < 0.0)
                    side = HalfSpace{-side->normal, -side->offset};
                if (!(side->distance(centre) > margin))
                    return std::nullopt;
                r.add(*side);
            }
    }
    return r;
}

}  // namespace occu
