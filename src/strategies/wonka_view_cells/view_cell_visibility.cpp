// SPDX-License-Identifier: MIT
#include "strategies/wonka_view_cells/view_cell_visibility.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "strategies/wonka_view_cells/footprint_shrinking.h"

namespace occu {

namespace {

double ms_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double cross(const glm::dvec2 &a, const glm::dvec2 &b)
{
    return a.x * b.y - a.y * b.x;
}

// Counter-clockwise convex hull (monotone chain) of a few points.
std::vector<glm::dvec2> convex_hull(std::vector<glm::dvec2> p)
{
    std::sort(p.begin(), p.end(), [](const glm::dvec2 &a, const glm::dvec2 &b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    std::vector<glm::dvec2> h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0.0)
            --k;
        h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross(h[k - 1] - h[k - 2], p[i - 1] - h[k - 2]) <= 0.0)
            --k;
        h[k++] = p[i - 1];
    }
    h.resize(k > 1 ? k - 1 : k);
    return h;
}

// Distance from q to a counter-clockwise convex polygon (0 inside).
double distance_to_hull(const std::vector<glm::dvec2> &hull, const glm::dvec2 &q)
{
    bool inside = true;
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0, j = hull.size() - 1; i < hull.size(); j = i++) {
        const glm::dvec2 a = hull[j], b = hull[i], ab = b - a;
        if (cross(ab, q - a) < 0.0)
            inside = false;
        const double len2 = glm::dot(ab, ab);
        const double t = len2 > 0.0 ? std::clamp(glm::dot(q - a, ab) / len2, 0.0, 1.0) : 0.0;
        d = std::min(d, glm::length(q - (a + t * ab)));
    }
    return inside ? 0.0 : d;
}

// Range maxima over one side of the horizon (a sparse table): the lowest
// umbra (the largest depth) among border pixels first..last.
class RangeMax {
public:
    explicit RangeMax(std::vector<std::uint32_t> values)
    {
        levels_.push_back(std::move(values));
        for (std::size_t w = 1; 2 * w <= levels_[0].size(); w *= 2) {
            const std::vector<std::uint32_t> &prev = levels_.back();
            std::vector<std::uint32_t> next(prev.size() - w);
            for (std::size_t i = 0; i < next.size(); ++i)
                next[i] = std::max(prev[i], prev[i + w]);
            levels_.push_back(std::move(next));
        }
    }
    std::uint32_t max(std::size_t first, std::size_t last) const
    {
        const std::size_t n = last - first + 1;
        std::size_t level = 0;
        while ((std::size_t(2) << level) <= n)
            ++level;
        return std::max(levels_[level][first], levels_[level][last + 1 - (std::size_t(1) << level)]);
    }

private:
    std::vector<std::vector<std::uint32_t>> levels_;
};

// The border pixels i = 0 .. n - 1 of one side, centres origin + i step, whose
// squares may meet the hull (centre within `reach` of it): an interval,
// since the distance to a convex set is convex along a line. False if none.
bool pixels_near_hull(const std::vector<glm::dvec2> &hull, const glm::dvec2 &origin, const glm::dvec2 &step, int n,
                      double reach, int &first, int &last)
{
    auto f = [&](int i) { return distance_to_hull(hull, origin + double(i) * step); };
    int lo = 0, hi = n - 1;
    while (hi - lo > 2) {   // ternary search for a minimum of a convex function
        const int m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        if (f(m1) <= f(m2))
            hi = m2;
        else
            lo = m1;
    }
    int best = lo;
    for (int i = lo + 1; i <= hi; ++i)
        if (f(i) < f(best))
            best = i;
    if (f(best) > reach)
        return false;
    int a = 0, b = best;   // the first index within reach: in [0, best]
    while (a < b) {
        const int m = (a + b) / 2;
        if (f(m) <= reach)
            b = m;
        else
            a = m + 1;
    }
    first = a;
    a = best, b = n - 1;   // the last: in [best, n - 1]
    while (a < b) {
        const int m = (a + b + 1) / 2;
        if (f(m) <= reach)
            a = m;
        else
            b = m - 1;
    }
    last = a;
    return true;
}

}  // namespace

const char *cull_map_test_name(CullMapTest test)
{
    return test == CullMapTest::readback ? "readback" : "occlusion-unit";
}

ViewCellVisibility::ViewCellVisibility(const Scene &scene, const Hierarchy &hierarchy, const ViewCells &cells,
                                       const ViewCellVisibilityOptions &options)
    : hierarchy_(hierarchy), cells_(cells), options_(options),
      map_(std::min(double(scene.bounds.min.y), cells.options().bottom) - 1.0,
           std::max(double(scene.bounds.max.y), cells.options().top) + 1.0)
{
    if (scene.prism_occluders.empty())
        throw std::invalid_argument(
            "view-cell visibility needs 2.5D occluders (prisms over footprints, Wonka et al. section 4.1): this "
            "scene has none (only the generated city knows its buildings' solids; a loaded scene's meshes do not "
            "say which are solid)");
    if (!(options.pixel > 0.0) || !std::isfinite(options.pixel) || !std::isfinite(options.epsilon) ||
        !(options.initial_extent > 0.0) || !std::isfinite(options.initial_extent))
        throw std::invalid_argument("view-cell visibility: epsilon, pixel size and initial extent must be finite and positive");
    // Section 2.2: shrinking by epsilon covers the cull map's sampling at
    // pixel centres only when epsilon >= k sqrt(2) / 2.
    if (!(options.epsilon >= options.pixel * std::sqrt(2.0) / 2.0))
        throw std::invalid_argument("view-cell visibility: epsilon " + std::to_string(options.epsilon) +
                                    " m is below k sqrt(2) / 2 = " + std::to_string(options.pixel * std::sqrt(2.0) / 2.0) +
                                    " m for cull map pixels of " + std::to_string(options.pixel) +
                                    " m (Wonka et al. section 2.2)");
    for (const PrismOccluder &o : scene.prism_occluders)
        for (PrismOccluder &part : shrink_footprint(o, options.epsilon)) {
            Aabb b;
            for (const glm::dvec2 &p : part.outline)
                b.expand(glm::vec3(float(p.x), float(part.top), float(p.y)));
            // Float bounds, grown a little: they only pick the occluders a map draws.
            b.min -= glm::vec3(0.01f);
            b.max += glm::vec3(0.01f);
            shrunk_.push_back(std::move(part));
            shrunk_bounds_.push_back(b);
        }
    const auto &nodes = hierarchy.nodes();
    for (std::uint32_t n = 0; n < nodes.size(); ++n)
        if (nodes[n].leaf() && !nodes[n].bounds.empty())
            leaves_.push_back(n);
    ground_min_ = {scene.bounds.min.x, scene.bounds.min.z};
    ground_max_ = {scene.bounds.max.x, scene.bounds.max.z};
    top_ = std::max(double(scene.bounds.max.y), cells.options().top);
}

CellVisibility ViewCellVisibility::compute(std::size_t cell, CullMapTest test)
{
    if (cell >= cells_.size())
        throw std::invalid_argument("view cell " + std::to_string(cell) + " of " + std::to_string(cells_.size()));
    if (test == CullMapTest::occlusion_unit && !unit_)
        unit_.emplace();
    CellVisibility out;
    const std::vector<glm::dvec3> samples = cells_.sample_points(cell, options_.epsilon);
    out.sample_points = samples.size();
    const ViewCells::Bounds cb = cells_.bounds(cell);
    const double k = options_.pixel;
    const double cell_top = cells_.options().top;
    const auto &nodes = hierarchy_.nodes();

    std::vector<std::uint32_t> undecided = leaves_;
    // Occluders still to draw: section 6 drops those the last map hides
    // (an occluder hidden from the whole cell shades only what is hidden already).
    std::vector<std::uint32_t> live_occluders(shrunk_.size());
    for (std::uint32_t i = 0; i < live_occluders.size(); ++i)
        live_occluders[i] = i;
    double half = options_.initial_extent;
    while (!undecided.empty()) {
        // The map: the cell and `half` around it, within the ground (and a
        // pixel more, so that objects on the ground's edge are inside).
        const glm::dvec2 lo_limit = ground_min_ - k, hi_limit = ground_max_ + k;
        const glm::dvec2 lo = glm::max(cb.min - half, lo_limit), hi = glm::min(cb.max + half, hi_limit);
        const bool whole = lo.x <= lo_limit.x && lo.y <= lo_limit.y && hi.x >= hi_limit.x && hi.y >= hi_limit.y;
        CullMapRegion region;
        region.pixel = k;
        region.min = glm::floor(lo / k) * k;
        region.width = std::max(1, int(std::ceil((hi.x - region.min.x) / k)));
        region.height = std::max(1, int(std::ceil((hi.y - region.min.y) / k)));
        const glm::dvec2 rmax = region.max();
        auto meets_region = [&](const Aabb &b) {
            return b.max.x >= region.min.x && b.min.x <= rmax.x && b.max.z >= region.min.y && b.min.z <= rmax.y;
        };

        auto start = std::chrono::steady_clock::now();
        std::vector<const PrismOccluder *> occluders;
        for (std::uint32_t i : live_occluders)
            if (meets_region(shrunk_bounds_[i]))
                occluders.push_back(&shrunk_[i]);
        map_.begin(region);
        for (const glm::dvec3 &p : samples)
            map_.add_sample_point(p, occluders);
        glFinish();   // the map is drawn: what follows is the test's time
        ++out.maps;
        out.occluders += occluders.size();
        out.map_pixels = std::size_t(region.width) * std::size_t(region.height);
        out.map_ms += ms_since(start);

        // Test the undecided objects, and the live occluders for the next
        // map, against this one.
        start = std::chrono::steady_clock::now();
        std::vector<Aabb> boxes;
        for (std::uint32_t n : undecided)
            boxes.push_back(nodes[n].bounds);
        // An occluder is tested with its footprint grown by a pixel: inside
        // it, its own shadow hides it from the map; the ring around it says
        // whether the others hide its walls. (Dropping an occluder wrongly
        // could only lose occlusion, never hide what is visible.)
        if (!whole)
            for (std::uint32_t i : live_occluders) {
                Aabb grown = shrunk_bounds_[i];
                grown.min -= glm::vec3(float(k), 0.0f, float(k));
                grown.max += glm::vec3(float(k), 0.0f, float(k));
                boxes.push_back(grown);
            }
        std::vector<std::optional<bool>> inside_visible(boxes.size());
        CullMap::Horizon horizon;
        std::chrono::steady_clock::time_point horizon_start;
        if (test == CullMapTest::readback) {
            const std::vector<std::uint32_t> depths = map_.read_depths();
            for (std::size_t i = 0; i < boxes.size(); ++i)
                inside_visible[i] = map_.visible_by_readback(boxes[i], depths);
            horizon_start = std::chrono::steady_clock::now();
            horizon = CullMap::horizon_of(region, depths);
        } else {
            std::size_t passes = 0;
            inside_visible = map_.visible_by_unit(*unit_, boxes, &passes);
            out.unit_passes += passes;
            horizon_start = std::chrono::steady_clock::now();
            horizon = map_.read_horizon();
        }

        // The horizon's four sides, for range maxima: bottom and top rows, left and right columns.
        struct Side {
            glm::dvec2 origin, step;
            int n;
            RangeMax depths;
        };
        auto side = [&](int x0, int y0, int dx, int dy, int n) {
            std::vector<std::uint32_t> d(static_cast<std::size_t>(n));
            for (int i = 0; i < n; ++i)
                d[std::size_t(i)] = horizon.at(x0 + i * dx, y0 + i * dy);
            return Side{region.min + k * glm::dvec2(x0 + 0.5, y0 + 0.5), k * glm::dvec2(dx, dy), n, RangeMax(std::move(d))};
        };
        const Side sides[4] = {side(0, 0, 1, 0, region.width), side(0, region.height - 1, 1, 0, region.width),
                               side(0, 0, 0, 1, region.height), side(region.width - 1, 0, 0, 1, region.height)};
        const double reach = k * std::sqrt(2.0) / 2.0;   // a pixel square around its centre
        // Hidden from the whole cell: by the map where the box is inside it,
        // and where it is not, by the horizon: every border pixel the
        // cell-to-box channel meets must hide the height a sight line can
        // have there.
        auto hidden = [&](const Aabb &box, const std::optional<bool> &visible_inside) {
            if (visible_inside.value_or(false))
                return false;
            if (box.min.x >= region.min.x && box.max.x <= rmax.x && box.min.z >= region.min.y && box.max.z <= rmax.y)
                return true;
            if (whole)
                return false;   // cannot happen (the last map holds the ground); conservatively visible
            const std::vector<glm::dvec2> hull = convex_hull({cb.min, {cb.max.x, cb.min.y}, cb.max, {cb.min.x, cb.max.y},
                                                             {box.min.x, box.min.z}, {box.max.x, box.min.z},
                                                             {box.max.x, box.max.z}, {box.min.x, box.max.z}});
            const std::uint32_t needed = map_.depth_of(std::max(cell_top, double(box.max.y)));
            for (const Side &sd : sides) {
                int first = 0, last = 0;
                if (pixels_near_hull(hull, sd.origin, sd.step, sd.n, reach, first, last) &&
                    sd.depths.max(std::size_t(first), std::size_t(last)) > needed)
                    return false;
            }
            return true;
        };

        std::vector<std::uint32_t> next;
        for (std::size_t i = 0; i < undecided.size(); ++i) {
            const std::uint32_t n = undecided[i];
            if (inside_visible[i].value_or(false))
                out.visible_leaves.push_back(n);   // seen in this map: visible, whatever lies beyond
            else if (!hidden(boxes[i], inside_visible[i]))
                next.push_back(n);
        }
        if (!whole) {
            std::vector<std::uint32_t> still_live;
            for (std::size_t j = 0; j < live_occluders.size(); ++j)
                if (!hidden(boxes[undecided.size() + j], inside_visible[undecided.size() + j]))
                    still_live.push_back(live_occluders[j]);
            live_occluders.swap(still_live);
        }
        out.horizon_ms += ms_since(horizon_start);
        out.test_ms += ms_since(start);
        undecided.swap(next);
        if (whole) {
            // Cannot happen (every box is inside the last map); conservatively visible.
            out.visible_leaves.insert(out.visible_leaves.end(), undecided.begin(), undecided.end());
            break;
        }
        half *= 2.0;
    }
    std::sort(out.visible_leaves.begin(), out.visible_leaves.end());
    return out;
}

}  // namespace occu
