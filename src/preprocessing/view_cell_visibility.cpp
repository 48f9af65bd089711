#include "preprocessing/view_cell_visibility.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "occluders/footprint_shrinking.h"

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

        auto start = std::chrono::steady_clock::now();
        std::vector<const PrismOccluder *> occluders;
        for (std::size_t i = 0; i < shrunk_.size(); ++i) {
            const Aabb &b = shrunk_bounds_[i];
            if (b.max.x >= region.min.x && b.min.x <= rmax.x && b.max.z >= region.min.y && b.min.z <= rmax.y)
                occluders.push_back(&shrunk_[i]);
        }
        map_.begin(region);
        for (const glm::dvec3 &p : samples)
            map_.add_sample_point(p, occluders);
        ++out.maps;
        out.occluders += occluders.size();
        out.map_pixels = std::size_t(region.width) * std::size_t(region.height);
        out.map_ms += ms_since(start);

        start = std::chrono::steady_clock::now();
        std::vector<std::optional<bool>> inside_visible(undecided.size());
        CullMap::Horizon horizon;
        if (test == CullMapTest::readback) {
            const std::vector<std::uint32_t> depths = map_.read_depths();
            for (std::size_t i = 0; i < undecided.size(); ++i)
                inside_visible[i] = map_.visible_by_readback(nodes[undecided[i]].bounds, depths);
            horizon = CullMap::horizon_of(region, depths);
        } else {
            std::vector<Aabb> boxes;
            for (std::uint32_t n : undecided)
                boxes.push_back(nodes[n].bounds);
            std::size_t passes = 0;
            inside_visible = map_.visible_by_unit(*unit_, boxes, &passes);
            out.unit_passes += passes;
            horizon = map_.read_horizon();
        }

        std::vector<std::uint32_t> next;
        const double reach = k * std::sqrt(2.0) / 2.0;   // a pixel square around its centre
        for (std::size_t i = 0; i < undecided.size(); ++i) {
            const std::uint32_t n = undecided[i];
            const Aabb &box = nodes[n].bounds;
            if (inside_visible[i].value_or(false)) {
                out.visible_leaves.push_back(n);
                continue;
            }
            const bool wholly_inside = box.min.x >= region.min.x && box.max.x <= rmax.x && box.min.z >= region.min.y &&
                                       box.max.z <= rmax.y;
            if (wholly_inside)
                continue;   // hidden by the map
            if (whole) {
                // Cannot happen (the last map holds the ground); keep it, conservatively.
                out.visible_leaves.push_back(n);
                continue;
            }
            // The horizon: every border pixel the cell-to-object channel
            // meets must hide the height a sight line can have there.
            const std::vector<glm::dvec2> hull = convex_hull({cb.min, {cb.max.x, cb.min.y}, cb.max, {cb.min.x, cb.max.y},
                                                             {box.min.x, box.min.z}, {box.max.x, box.min.z},
                                                             {box.max.x, box.max.z}, {box.min.x, box.max.z}});
            const std::uint32_t needed = map_.depth_of(std::max(cell_top, double(box.max.y)));
            bool hidden = true;
            auto check = [&](int x, int y) {
                const glm::dvec2 centre = region.min + k * glm::dvec2(x + 0.5, y + 0.5);
                if (distance_to_hull(hull, centre) <= reach && horizon.at(x, y) > needed)
                    hidden = false;
            };
            for (int x = 0; x < region.width && hidden; ++x) {
                check(x, 0);
                check(x, region.height - 1);
            }
            for (int y = 0; y < region.height && hidden; ++y) {
                check(0, y);
                check(region.width - 1, y);
            }
            if (!hidden)
                next.push_back(n);
        }
        out.test_ms += ms_since(start);
        undecided.swap(next);
        if (whole)
            break;
        half *= 2.0;
    }
    std::sort(out.visible_leaves.begin(), out.visible_leaves.end());
    return out;
}

}  // namespace occu
