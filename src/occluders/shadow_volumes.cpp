// Shadow frusta and supporting planes (Moeller and Haines, "Occlusion
// Culling Algorithms", section "Shadow Culling"): see shadow_volumes.h for
// the statements and their proofs.
#include "occluders/shadow_volumes.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace occu {

namespace {

glm::dvec3 lo(const Aabb &b) { return glm::dvec3(b.min); }
glm::dvec3 hi(const Aabb &b) { return glm::dvec3(b.max); }

glm::dvec3 axis_vector(int axis)
{
    glm::dvec3 v(0.0);
    v[axis] = 1.0;
    return v;
}

// A plane through `point` with the (not yet unit) normal `normal`; empty
// when the normal has no length to speak of.
std::optional<HalfSpace> plane_through(const glm::dvec3 &point, const glm::dvec3 &normal)
{
    const double length = glm::length(normal);
    if (!(length > 0.0) || !std::isfinite(length))
        return std::nullopt;
    const glm::dvec3 n = normal / length;
    return HalfSpace{n, -glm::dot(n, point)};
}

// What polygon_shadow and polygon_supporting_planes need of a polygon: its
// unit normal along the winding (Newell's), its edges of nonzero length,
// and whether it is a convex polygon with area.
struct PolygonFacts {
    glm::dvec3 normal{0.0};
    std::vector<std::pair<glm::dvec3, glm::dvec3>> edges;   // (start, end)
    double margin = 0.0;
};

std::optional<PolygonFacts> polygon_facts(const std::vector<glm::dvec3> &polygon, double margin)
{
    const std::size_t n = polygon.size();
    if (n < 3)
        return std::nullopt;
    PolygonFacts f;
    f.margin = margin;
    glm::dvec3 newell(0.0);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 &a = polygon[i], &b = polygon[(i + 1) % n];
        newell += glm::cross(a, b);
        // Edges no longer than the margin are taken as repeated vertices:
        // their neighbours bound the same shadow.
        if (glm::length(b - a) > margin)
            f.edges.emplace_back(a, b);
    }
    // Twice the area: a sliver is no occluder (its side planes would be
    // unreliable, and it hides nothing).
    const double twice_area = glm::length(newell);
    if (f.edges.size() < 3 || !(twice_area > margin * margin * 4.0) || !std::isfinite(twice_area))
        return std::nullopt;
    f.normal = newell / twice_area;
    // Convex: every turn from one edge to the next goes the winding's way
    // (collinear edges allowed, with a tolerance relative to the edges).
    for (std::size_t i = 0; i < f.edges.size(); ++i) {
        const glm::dvec3 e0 = f.edges[i].second - f.edges[i].first;
        const glm::dvec3 e1 = f.edges[(i + 1) % f.edges.size()].second - f.edges[(i + 1) % f.edges.size()].first;
        if (glm::dot(glm::cross(e0, e1), f.normal) < -1e-12 * glm::length(e0) * glm::length(e1))
            return std::nullopt;
    }
    return f;
}

// The extent of the polygon along `n`: [min, max] of dot(n, vertex). A
// polygon made of floats is not exactly planar; taking its farthest
// vertices keeps every statement conservative.
std::pair<double, double> extent_along(const std::vector<glm::dvec3> &polygon, const glm::dvec3 &n)
{
    double a = glm::dot(n, polygon[0]), b = a;
    for (const glm::dvec3 &v : polygon) {
        a = std::min(a, glm::dot(n, v));
        b = std::max(b, glm::dot(n, v));
    }
    return {a, b};
}

double polygon_magnitude(const std::vector<glm::dvec3> &polygon)
{
    double m = 0.0;
    for (const glm::dvec3 &v : polygon)
        m = std::max(m, magnitude(v));
    return m;
}

double max_corner_along(const Aabb &box, const glm::dvec3 &n)
{
    const glm::dvec3 c{n.x >= 0 ? box.max.x : box.min.x, n.y >= 0 ? box.max.y : box.min.y,
                       n.z >= 0 ? box.max.z : box.min.z};
    return glm::dot(n, c);
}

double min_corner_along(const Aabb &box, const glm::dvec3 &n) { return -max_corner_along(box, -n); }

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

double HalfSpace::min_distance(const Aabb &box) const { return min_corner_along(box, normal) + offset; }

bool ConvexRegion::holds(const glm::dvec3 &p) const
{
    const double m = std::max(margin, shadow_margin(magnitude(p)));
    for (int i = 0; i < count; ++i)
        if (!(planes[std::size_t(i)].distance(p) > m))
            return false;
    return true;
}

bool ConvexRegion::holds(const Aabb &box) const
{
    if (box.empty())
        return false;
    const double m = std::max(margin, shadow_margin(magnitude(box)));
    for (int i = 0; i < count; ++i)
        if (!(planes[std::size_t(i)].min_distance(box) > m))
            return false;
    return count > 0;
}

double shadow_margin(double magnitude) { return 1e-9 * (1.0 + magnitude); }

double magnitude(const glm::dvec3 &p) { return std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}); }

double magnitude(const Aabb &box) { return std::max(magnitude(lo(box)), magnitude(hi(box))); }

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

std::vector<glm::dvec3> box_face(const Aabb &box, int face)
{
    const int a = face / 2, u = (a + 1) % 3, v = (a + 2) % 3;
    const bool max_side = face % 2 == 1;
    glm::dvec3 p(0.0);
    p[a] = max_side ? double(box.max[a]) : double(box.min[a]);
    auto at = [&](bool hu, bool hv) {
        glm::dvec3 q = p;
        q[u] = hu ? double(box.max[u]) : double(box.min[u]);
        q[v] = hv ? double(box.max[v]) : double(box.min[v]);
        return q;
    };
    // e_u x e_v = e_a: (u, v) counter-clockwise is counter-clockwise seen
    // from +a, the max face's outside; the min face goes the other way.
    if (max_side)
        return {at(false, false), at(true, false), at(true, true), at(false, true)};
    return {at(false, false), at(false, true), at(true, true), at(true, false)};
}

glm::dvec3 box_face_normal(int face) { return (face % 2 ? 1.0 : -1.0) * axis_vector(face / 2); }

std::optional<unsigned> front_faces(const glm::dvec3 &eye, const Aabb &box, double margin)
{
    unsigned mask = 0;
    for (int a = 0; a < 3; ++a) {
        const double l = box.min[a], h = box.max[a], e = eye[a];
        if (e < l - margin)
            mask |= 1u << (2 * a);
        else if (e > h + margin)
            mask |= 1u << (2 * a + 1);
        else if (!(e > l + margin && e < h - margin))
            return std::nullopt;   // within the margin of a face's plane (or a degenerate axis)
    }
    if (mask == 0)
        return std::nullopt;       // the eye is inside
    return mask;
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
