// SPDX-License-Identifier: MIT
// Coorg and Teller's supporting planes (Moeller and Haines, "Occlusion
// Culling Algorithms", section "Shadow Culling"): see supporting_planes.h
// for the statements and their proofs.
#include "strategies/coorg_teller_supporting_planes/supporting_planes.h"

#include <algorithm>
#include <tuple>

namespace occu {

namespace {

// Coorg and Teller's supporting plane through the edge at `origin` (a
// point of the edge's line), in the plane across the edge: `inward` points
// from the edge into the occluder, `behind` away from the viewers' side,
// both unit and perpendicular to the edge and to each other. The occluder
// fills the directions from angle 0 (inward) up to `floor` (inward itself
// for a polygon; `behind` for a box aggregate's silhouette edge, whose
// back face runs that way). The box's corners, all strictly behind, lie at
// angles in (0, pi); the supporting plane is the line at the largest
// angle of the occluder and the box together (the one tangent that keeps
// both on one side; the other tangent through the edge separates them),
// and the viewer must be on their side of it.
HalfSpace supporting_plane(const glm::dvec3 &origin, const glm::dvec3 &inward, const glm::dvec3 &behind,
                           const glm::dvec2 &floor, const Aabb &box)
{
    glm::dvec2 t = floor;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 q = glm::dvec3(box.corner(i)) - origin;
        const glm::dvec2 c(glm::dot(q, inward), glm::dot(q, behind));
        // Both in the upper half-plane: c is at a larger angle than t iff
        // it lies to the left of t.
        if (t.x * c.y - t.y * c.x > 0.0)
            t = c;
    }
    // The line's normal towards the smaller angles (the occluder's and the
    // box's side): t turned clockwise, (t.y, -t.x), in 3D with -behind the
    // viewers' direction.
    const glm::dvec3 n = t.y * inward + t.x * -behind;
    return *plane_through(origin, n);   // |n| = |t| > 0: t is floor or a corner strictly behind
}

}  // namespace

std::optional<ConvexRegion> polygon_supporting_planes(const std::vector<glm::dvec3> &polygon, const Aabb &box)
{
    if (box.empty())
        return std::nullopt;
    const double margin = shadow_margin(std::max(polygon_magnitude(polygon), magnitude(box)));
    const auto facts = polygon_facts(polygon, margin);
    if (!facts)
        return std::nullopt;
    // The viewers' side of the polygon is the one away from the box; the
    // box must be strictly on the other.
    glm::dvec3 front = facts->normal;
    auto [near, far] = extent_along(polygon, front);
    if (!(max_corner_along(box, front) < near - margin)) {
        front = -front;
        std::tie(near, far) = std::make_pair(-far, -near);
        if (!(max_corner_along(box, front) < near - margin))
            return std::nullopt;   // the box reaches the polygon's plane
    }
    ConvexRegion r;
    r.margin = margin;
    r.add(HalfSpace{front, -far});   // the viewer in front of every vertex
    for (const auto &[a, b] : facts->edges) {
        // Inward from the edge within the polygon: the winding normal
        // crossed with the edge (counter-clockwise around that normal).
        const glm::dvec3 inward = glm::normalize(glm::cross(facts->normal, b - a));
        if (r.count == int(r.planes.size()))
            return std::nullopt;
        r.add(supporting_plane(a, inward, -front, glm::dvec2(1.0, 0.0), box));
    }
    return r;
}

std::optional<ConvexRegion> box_supporting_planes(const Aabb &occluder, unsigned front, const Aabb &box)
{
    if (box.empty() || front == 0)
        return std::nullopt;
    const double margin = shadow_margin(std::max(magnitude(occluder), magnitude(box)));
    ConvexRegion r;
    r.margin = margin;
    for (int a = 0; a < 3; ++a) {
        const unsigned bits = (front >> (2 * a)) & 3u;
        const double l = occluder.min[a], h = occluder.max[a];
        if (!(h - l > margin) || bits == 3u)
            return std::nullopt;
        const glm::dvec3 e = axis_vector(a);
        // The box strictly behind each front face, the viewer strictly in
        // front of it; between the planes of an axis whose faces it sees
        // neither of.
        if (bits == 1u) {
            if (!(double(box.min[a]) > l + margin))
                return std::nullopt;
            r.add(HalfSpace{-e, l});
        } else if (bits == 2u) {
            if (!(double(box.max[a]) < h - margin))
                return std::nullopt;
            r.add(HalfSpace{e, -h});
        } else {
            r.add(HalfSpace{e, -l});
            r.add(HalfSpace{-e, h});
        }
    }
    // One supporting plane per silhouette edge: in the plane across the
    // edge the occluder fills the quarter from its front face's inward
    // direction (away from the back face) to `behind` (along the back face).
    for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        for (int si = 0; si < 2; ++si)
            for (int sj = 0; sj < 2; ++sj) {
                const int face_i = 2 * i + si, face_j = 2 * j + sj;
                const bool fi = front & (1u << face_i), fj = front & (1u << face_j);
                if (fi == fj)
                    continue;
                const int f = fi ? face_i : face_j, g = fi ? face_j : face_i;
                glm::dvec3 origin(0.0);
                origin[i] = si ? occluder.max[i] : occluder.min[i];
                origin[j] = sj ? occluder.max[j] : occluder.min[j];
                origin[k] = occluder.min[k];
                r.add(supporting_plane(origin, -box_face_normal(g), -box_face_normal(f), glm::dvec2(0.0, 1.0), box));
            }
    }
    return r;
}

}  // namespace occu
