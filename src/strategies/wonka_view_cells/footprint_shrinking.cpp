// SPDX-License-Identifier: MIT
#include "strategies/wonka_view_cells/footprint_shrinking.h"

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

namespace {

void check_footprint(const PrismOccluder &footprint)
{
    if (footprint.outline.size() < 3 || !finite(footprint.outline))
        throw std::invalid_argument("a footprint needs at least 3 finite points (within 1e9 m)");
    for (const auto &hole : footprint.holes)
        if (hole.size() < 3 || !finite(hole))
            throw std::invalid_argument("a footprint's hole needs at least 3 finite points (within 1e9 m)");
}

// The footprint's rings as Clipper paths: outline positive, holes negative,
// whatever the input's windings.
ClipperLib::Paths footprint_paths(const PrismOccluder &footprint)
{
    ClipperLib::Paths paths{to_path(footprint.outline)};
    for (const auto &hole : footprint.holes)
        paths.push_back(to_path(hole));
    if (!ClipperLib::Orientation(paths[0]))
        ClipperLib::ReversePath(paths[0]);
    for (std::size_t i = 1; i < paths.size(); ++i)
        if (ClipperLib::Orientation(paths[i]))
            ClipperLib::ReversePath(paths[i]);
    return paths;
}

// The outer rings of a Clipper tree with their holes, as footprints.
std::vector<PrismOccluder> footprints_of(const ClipperLib::PolyTree &tree, double bottom, double top)
{
    std::vector<PrismOccluder> parts;
    std::vector<const ClipperLib::PolyNode *> stack(tree.Childs.begin(), tree.Childs.end());
    while (!stack.empty()) {
        const ClipperLib::PolyNode *node = stack.back();
        stack.pop_back();
        if (node->IsHole())
            continue;
        PrismOccluder part;
        part.bottom = bottom;
        part.top = top;
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

}  // namespace

std::vector<PrismOccluder> shrink_footprint(const PrismOccluder &footprint, double epsilon)
{
    if (!(epsilon >= 0.0) || !std::isfinite(epsilon))
        throw std::invalid_argument("occluder shrinking by " + std::to_string(epsilon) + " m: want a finite epsilon >= 0");
    check_footprint(footprint);
    ClipperLib::ClipperOffset offset;
    offset.AddPaths(footprint_paths(footprint), ClipperLib::jtSquare, ClipperLib::etClosedPolygon);
    ClipperLib::PolyTree tree;
    offset.Execute(tree, -(epsilon * clipper_units_per_metre + 1.0));
    return footprints_of(tree, footprint.bottom, footprint.top);
}

std::vector<PrismOccluder> grown_union(const std::vector<PrismOccluder> &footprints, double margin, double close_gaps)
{
    if (!(margin >= 0.0) || !std::isfinite(margin) || !(close_gaps >= 0.0) || !std::isfinite(close_gaps))
        throw std::invalid_argument("growing footprints by " + std::to_string(margin) + " m, closing gaps of " +
                                    std::to_string(close_gaps) + " m: want finite values >= 0");
    ClipperLib::ClipperOffset grow;
    for (const PrismOccluder &f : footprints) {
        check_footprint(f);
        grow.AddPaths(footprint_paths(f), ClipperLib::jtSquare, ClipperLib::etClosedPolygon);
    }
    // One offset of every path at once: overlapping results come out as their union.
    ClipperLib::Paths grown;
    grow.Execute(grown, margin * clipper_units_per_metre + 1.0);
    ClipperLib::Clipper all;
    all.AddPaths(grown, ClipperLib::ptSubject, true);
    if (close_gaps > 0.0) {
        // Grown by half the gap and shrunk back: gaps narrower than it fill.
        // Square joins make the shrink cut corners, so the union with the
        // grown footprints keeps every point within margin of a footprint.
        const double half = 0.5 * close_gaps * clipper_units_per_metre;
        ClipperLib::ClipperOffset out, in;
        ClipperLib::Paths wide, closed;
        out.AddPaths(grown, ClipperLib::jtSquare, ClipperLib::etClosedPolygon);
        out.Execute(wide, half);
        in.AddPaths(wide, ClipperLib::jtSquare, ClipperLib::etClosedPolygon);
        in.Execute(closed, -half);
        all.AddPaths(closed, ClipperLib::ptClip, true);
    }
    ClipperLib::PolyTree tree;
    all.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    return footprints_of(tree, 0.0, 0.0);
}

}  // namespace occu
