// SPDX-License-Identifier: MIT
#include "strategies/wonka_view_cells/view_cells.h"

#include <algorithm>
#include <cmath>
#include <list>
#include <stdexcept>
#include <string>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "strategies/wonka_view_cells/footprint_shrinking.h"

namespace occu {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Tds = CGAL::Triangulation_data_structure_2<CGAL::Delaunay_mesh_vertex_base_2<Kernel>,
                                                 CGAL::Delaunay_mesh_face_base_2<Kernel>>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Point = Cdt::Point;

constexpr std::size_t max_cells = std::size_t(1) << 22;

bool finite(const glm::dvec2 &p)
{
    return std::isfinite(p.x) && std::isfinite(p.y);
}

double cross(const glm::dvec2 &a, const glm::dvec2 &b)
{
    return a.x * b.y - a.y * b.x;
}

// A point strictly inside a simple polygon (outline and holes): the
// centroid of an ear-like triangle of its constrained triangulation would
// do; a cheaper one: the midpoint of the widest horizontal chord at the
// height of a vertex nudged off it.
glm::dvec2 interior_point(const PrismOccluder &f)
{
    double y = 0.5 * (f.outline[0].y + f.outline[1].y);
    for (const glm::dvec2 &p : f.outline)
        if (p.y != f.outline[0].y) {
            y = 0.5 * (f.outline[0].y + p.y);
            break;
        }
    // Crossings of the line z = y with every edge, sorted: pairs are inside spans.
    std::vector<double> xs;
    auto ring = [&](const std::vector<glm::dvec2> &poly) {
        for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
            if ((poly[i].y > y) != (poly[j].y > y))
                xs.push_back(poly[j].x + (y - poly[j].y) * (poly[i].x - poly[j].x) / (poly[i].y - poly[j].y));
    };
    ring(f.outline);
    for (const auto &h : f.holes)
        ring(h);
    std::sort(xs.begin(), xs.end());
    double best = -1.0, x = f.outline[0].x;
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2)
        if (xs[i + 1] - xs[i] > best) {
            best = xs[i + 1] - xs[i];
            x = 0.5 * (xs[i] + xs[i + 1]);
        }
    return {x, y};
}

}  // namespace

ViewCells::ViewCells(const glm::dvec2 &ground_min, const glm::dvec2 &ground_max, const std::vector<PrismOccluder> &footprints,
                     const ViewCellOptions &options)
    : options_(options)
{
    if (!finite(ground_min) || !finite(ground_max) || !(ground_min.x < ground_max.x) || !(ground_min.y < ground_max.y))
        throw std::invalid_argument("view cells need a finite, non-empty ground rectangle");
    if (!(options.max_edge > 0.0) || !std::isfinite(options.max_edge))
        throw std::invalid_argument("view cells: the maximum edge length must be finite and positive, got " +
                                    std::to_string(options.max_edge));
    const glm::dvec2 size = ground_max - ground_min;
    // An equilateral triangle of edge max_edge has area 0.433 max_edge^2.
    if (size.x * size.y / (0.433 * options.max_edge * options.max_edge) > double(max_cells))
        throw std::invalid_argument("view cells: a maximum edge of " + std::to_string(options.max_edge) +
                                    " m over this ground needs more than 2^22 cells");
    if (!(options.bottom < options.top) || !std::isfinite(options.bottom) || !std::isfinite(options.top))
        throw std::invalid_argument("view cells: the prisms' bottom must be below their top");

    Cdt cdt;
    const Point corners[4] = {{ground_min.x, ground_min.y}, {ground_max.x, ground_min.y},
                              {ground_max.x, ground_max.y}, {ground_min.x, ground_max.y}};
    for (int i = 0; i < 4; ++i)
        cdt.insert_constraint(corners[i], corners[(i + 1) % 4]);
    if (!(options.clearance >= 0.0) || !std::isfinite(options.clearance) || !(options.close_gaps >= 0.0) ||
        !std::isfinite(options.close_gaps))
        throw std::invalid_argument("view cells: the clearance and the gaps closed must be finite and >= 0");
    std::list<Point> seeds;
    for (const PrismOccluder &f : grown_union(footprints, options.clearance, options.close_gaps)) {
        if (f.outline.size() < 3)
            throw std::invalid_argument("a footprint with fewer than 3 points");
        auto ring = [&](const std::vector<glm::dvec2> &poly) {
            for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
                if (!finite(poly[i]))
                    throw std::invalid_argument("a footprint with a point that is not finite");
                cdt.insert_constraint(Point(poly[j].x, poly[j].y), Point(poly[i].x, poly[i].y));
            }
        };
        ring(f.outline);
        for (const auto &h : f.holes)
            ring(h);
        // The seed marks the footprint's inside as not to be meshed (its
        // courtyards, bounded by the holes, are free space again).
        seeds.emplace_back(interior_point(f).x, interior_point(f).y);
    }
    // Size only (shape bound 0): every edge at most max_edge, no angle
    // refinement that would fill the narrow gaps between buildings with
    // slivers of cells.
    CGAL::refine_Delaunay_mesh_2(cdt, seeds.begin(), seeds.end(), Criteria(0.0, options.max_edge));

    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        if (!f->is_in_domain())
            continue;
        std::array<glm::dvec2, 3> t;
        for (int i = 0; i < 3; ++i)
            t[std::size_t(i)] = {f->vertex(i)->point().x(), f->vertex(i)->point().y()};
        if (cross(t[1] - t[0], t[2] - t[0]) < 0.0)
            std::swap(t[1], t[2]);
        triangles_.push_back(t);
    }
    // Ground rectangles bounded by footprints could leave none.
    if (triangles_.empty())
        throw std::invalid_argument("view cells: the footprints leave no free space on the ground");
    // A deterministic order: by the triangles' lowest corner, row by row.
    std::sort(triangles_.begin(), triangles_.end(), [](const auto &a, const auto &b) {
        auto key = [](const std::array<glm::dvec2, 3> &t) {
            const glm::dvec2 c = (t[0] + t[1] + t[2]) / 3.0;
            return std::pair(c.y, c.x);
        };
        return key(a) < key(b);
    });
    build_grid();
}

ViewCells::ViewCells(std::vector<std::array<glm::dvec2, 3>> triangles, const ViewCellOptions &options)
    : triangles_(std::move(triangles)), options_(options)
{
    if (triangles_.empty() || triangles_.size() > max_cells)
        throw std::invalid_argument("view cells: " + std::to_string(triangles_.size()) + " cells (want 1 to 2^22)");
    if (!(options.bottom < options.top) || !std::isfinite(options.bottom) || !std::isfinite(options.top))
        throw std::invalid_argument("view cells: the prisms' bottom must be below their top");
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
        auto &t = triangles_[i];
        for (const glm::dvec2 &p : t)
            if (!finite(p) || std::abs(p.x) > 1e9 || std::abs(p.y) > 1e9)
                throw std::invalid_argument("view cell " + std::to_string(i) +
                                            " has a corner that is not finite or beyond 1e9 m");
        const double area2 = cross(t[1] - t[0], t[2] - t[0]);
        if (area2 == 0.0)
            throw std::invalid_argument("view cell " + std::to_string(i) + " has no area");
        if (area2 < 0.0)
            std::swap(t[1], t[2]);
    }
    build_grid();
}

ViewCells::Bounds ViewCells::bounds(std::size_t cell) const
{
    const auto &t = triangles_[cell];
    return {glm::min(t[0], glm::min(t[1], t[2])), glm::max(t[0], glm::max(t[1], t[2]))};
}

void ViewCells::build_grid()
{
    glm::dvec2 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    double mean_size = 0.0;
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
        const Bounds b = bounds(i);
        lo = glm::min(lo, b.min);
        hi = glm::max(hi, b.max);
        mean_size += std::max(b.max.x - b.min.x, b.max.y - b.min.y);
    }
    mean_size /= double(triangles_.size());
    // About one cell per grid square.
    const double square = std::max(mean_size, 1e-9 + 1e-12 * std::max(hi.x - lo.x, hi.y - lo.y));
    grid_min_ = lo;
    // Clamped in double: a far-flung cell must not overflow an int.
    grid_size_ = glm::ivec2(int(std::clamp((hi.x - lo.x) / square + 1.0, 1.0, 4096.0)),
                            int(std::clamp((hi.y - lo.y) / square + 1.0, 1.0, 4096.0)));
    grid_cell_ = glm::max((hi - lo) / glm::dvec2(grid_size_), glm::dvec2(1e-12));
    grid_.assign(std::size_t(grid_size_.x) * std::size_t(grid_size_.y), {});
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
        const Bounds b = bounds(i);
        const glm::dvec2 top(grid_size_ - 1);
        const glm::ivec2 g0(glm::clamp(glm::floor((b.min - grid_min_) / grid_cell_), glm::dvec2(0.0), top));
        const glm::ivec2 g1(glm::clamp(glm::floor((b.max - grid_min_) / grid_cell_), glm::dvec2(0.0), top));
        for (int y = g0.y; y <= g1.y; ++y)
            for (int x = g0.x; x <= g1.x; ++x)
                grid_[std::size_t(y) * std::size_t(grid_size_.x) + std::size_t(x)].push_back(std::uint32_t(i));
    }
}

std::optional<std::uint32_t> ViewCells::locate(const glm::vec3 &eye) const
{
    const glm::dvec2 p(eye.x, eye.z);
    if (!finite(p) || !std::isfinite(eye.y) || double(eye.y) < options_.bottom || double(eye.y) > options_.top)
        return std::nullopt;
    const glm::dvec2 g = glm::floor((p - grid_min_) / grid_cell_);
    if (g.x < 0.0 || g.y < 0.0 || g.x > double(grid_size_.x) || g.y > double(grid_size_.y))
        return std::nullopt;
    const glm::ivec2 gi = glm::min(glm::ivec2(g), grid_size_ - 1);
    for (std::uint32_t i : grid_[std::size_t(gi.y) * std::size_t(grid_size_.x) + std::size_t(gi.x)]) {
        const auto &t = triangles_[i];
        if (cross(t[1] - t[0], p - t[0]) >= 0.0 && cross(t[2] - t[1], p - t[1]) >= 0.0 &&
            cross(t[0] - t[2], p - t[2]) >= 0.0)
            return i;
    }
    return std::nullopt;
}

std::vector<glm::dvec3> ViewCells::sample_points(std::size_t cell, double epsilon) const
{
    if (!(epsilon > 0.0) || !std::isfinite(epsilon))
        throw std::invalid_argument("sample spacing epsilon must be finite and positive, got " + std::to_string(epsilon));
    const auto &t = triangles_[cell];
    std::vector<glm::dvec3> points;
    for (int e = 0; e < 3; ++e) {
        const glm::dvec2 a = t[std::size_t(e)], b = t[std::size_t((e + 1) % 3)];
        // n segments of at most 2 epsilon: every point within epsilon of an end.
        const int n = std::max(1, int(std::ceil(glm::length(b - a) / (2.0 * epsilon))));
        for (int i = 0; i < n; ++i) {   // the edge's end is the next edge's start
            const glm::dvec2 p = a + (b - a) * (double(i) / double(n));
            points.emplace_back(p.x, options_.top, p.y);
        }
    }
    return points;
}

}  // namespace occu
