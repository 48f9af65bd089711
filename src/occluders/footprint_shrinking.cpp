#include "occluders/footprint_shrinking.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <polyclipping/clipper.hpp>

namespace occu {

namespace {

constexpr double clipper_units_per_metre = 1e4;

ClipperLib::Path to_path(const std::vector<glm::dvec2> &polygon)
{
    ClipperLib::Path path;
    for (const glm::dvec2 &p : polygon)
        path.emplace_back(ClipperLib::cInt(std::llround(p.x * clipper_units_per_metre)),
                          ClipperLib::cInt(std::llround(p.y * clipper_units_per_metre)));
    return path;
}

std::vector<glm::dvec2> from_path(const ClipperLib::Path &path)
{
    std::vector<glm::dvec2> polygon;
    for (const ClipperLib::IntPoint &p : path)
        polygon.emplace_back(double(p.X) / clipper_units_per_metre, double(p.Y) / clipper_units_per_metre);
    return polygon;
}

bool finite(const std::vector<glm::dvec2> &polygon)
{
    for (const glm::dvec2 &p : polygon)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || std::abs(p.x) > 1e9 || std::abs(p.y) > 1e9)
            return false;
    return true;
}

double distance_to_segment(const glm::dvec2 &p, const glm::dvec2 &a, const glm::dvec2 &b)
{
    const glm::dvec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * ab));
}

bool inside_polygon(const std::vector<glm::dvec2> &poly, const glm::dvec2 &p)
{
    bool in = false;
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
        if ((poly[i].y > p.y) != (poly[j].y > p.y) &&
            p.x < (poly[j].x - poly[i].x) * (p.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x)
            in = !in;
    return in;
}

}  // namespace

double signed_area(const std::vector<glm::dvec2> &polygon)
{
    double a = 0.0;
    for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
        a += polygon[j].x * polygon[i].y - polygon[i].x * polygon[j].y;
    return 0.5 * a;
}

bool inside(const PrismOccluder &footprint, const glm::dvec2 &p)
{
    bool in = inside_polygon(footprint.outline, p);
    for (const auto &hole : footprint.holes)
        in = in != inside_polygon(hole, p);
    return in;
}

double depth_inside(const PrismOccluder &footprint, const glm::dvec2 &p)
{
    if (!inside(footprint, p))
        return 0.0;
    double d = std::numeric_limits<double>::infinity();
    auto ring = [&](const std::vector<glm::dvec2> &poly) {
        for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
            d = std::min(d, distance_to_segment(p, poly[j], poly[i]));
    };
    ring(footprint.outline);
    for (const auto &hole : footprint.holes)
        ring(hole);
    return d;
}

std::vector<PrismOccluder> shrink_footprint(const PrismOccluder &footprint, double epsilon)
{
    if (!(epsilon >= 0.0) || !std::isfinite(epsilon))
        throw std::invalid_argument("occluder shrinking by " + std::to_string(epsilon) + " m: want a finite epsilon >= 0");
    if (footprint.outline.size() < 3 || !finite(footprint.outline))
        throw std::invalid_argument("a footprint needs at least 3 finite points (within 1e9 m)");
    for (const auto &hole : footprint.holes)
        if (hole.size() < 3 || !finite(hole))
            throw std::invalid_argument("a footprint's hole needs at least 3 finite points (within 1e9 m)");

    ClipperLib::Paths paths{to_path(footprint.outline)};
    for (const auto &hole : footprint.holes)
        paths.push_back(to_path(hole));
    // Whatever the input's windings: outline positive, holes negative.
    if (!ClipperLib::Orientation(paths[0]))
        ClipperLib::ReversePath(paths[0]);
    for (std::size_t i = 1; i < paths.size(); ++i)
        if (ClipperLib::Orientation(paths[i]))
            ClipperLib::ReversePath(paths[i]);

    ClipperLib::ClipperOffset offset;
    offset.AddPaths(paths, ClipperLib::jtSquare, ClipperLib::etClosedPolygon);
    ClipperLib::PolyTree tree;
    offset.Execute(tree, -(epsilon * clipper_units_per_metre + 1.0));

    std::vector<PrismOccluder> parts;
    // Outer rings are the tree's non-hole nodes, their children the holes.
    std::vector<const ClipperLib::PolyNode *> stack(tree.Childs.begin(), tree.Childs.end());
    while (!stack.empty()) {
        const ClipperLib::PolyNode *node = stack.back();
        stack.pop_back();
        if (node->IsHole())
            continue;
        PrismOccluder part;
        part.bottom = footprint.bottom;
        part.top = footprint.top;
        part.outline = from_path(node->Contour);
        if (signed_area(part.outline) < 0.0)
            std::reverse(part.outline.begin(), part.outline.end());
        for (const ClipperLib::PolyNode *hole : node->Childs) {
            std::vector<glm::dvec2> ring = from_path(hole->Contour);
            if (signed_area(ring) > 0.0)
                std::reverse(ring.begin(), ring.end());
            part.holes.push_back(std::move(ring));
            // Islands inside a hole are outer rings again.
            for (const ClipperLib::PolyNode *island : hole->Childs)
                stack.push_back(island);
        }
        parts.push_back(std::move(part));
    }
    return parts;
}

}  // namespace occu
