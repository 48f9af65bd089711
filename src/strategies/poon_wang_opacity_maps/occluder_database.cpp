// SPDX-License-Identifier: MIT
#include "strategies/poon_wang_opacity_maps/occluder_database.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <limits>
#include <stdexcept>

namespace occu {

namespace {

constexpr float two_pi = 6.28318530718f;

// Heading d of `directions`: at angle 2 pi d / directions from +x towards +z.
glm::vec3 heading(int d, int directions)
{
    const float a = two_pi * float(d) / float(directions);
    return {std::cos(a), 0.0f, std::sin(a)};
}

// The camera's view direction as a heading angle in [0, 2 pi).
float heading_angle(const Camera &camera)
{
    const glm::vec3 f = camera.target - camera.position;
    const float angle = std::atan2(f.z, f.x);
    return angle < 0.0f ? angle + two_pi : angle;
}

}  // namespace

std::string grid_settings(const OccluderGrid &g)
{
    auto triple = [](const auto &v) { return exact_number(v.x) + "," + exact_number(v.y) + "," + exact_number(v.z); };
    return "grid-origin=" + triple(g.origin) + " grid-spacing=" + triple(g.spacing) + " grid-points=" +
           std::to_string(g.points.x) + "," + std::to_string(g.points.y) + "," + std::to_string(g.points.z) +
           " headings=" + std::to_string(g.directions);
}

OccluderGrid OccluderGrid::over_scene(const Aabb &bounds, const glm::ivec3 &points, int directions, float eye_height)
{
    OccluderGrid g;
    g.points = points;
    g.directions = directions;
    const glm::vec3 size = bounds.extent();
    auto step = [](float extent, int n) { return n > 1 ? extent / float(n - 1) : 0.0f; };
    g.spacing = {step(size.x, points.x), step(size.y, points.y), step(size.z, points.z)};
    // One point across an axis stands at the middle of it.
    auto first = [](float lo, float extent, int n) { return n > 1 ? lo : lo + 0.5f * extent; };
    g.origin = {first(bounds.min.x, size.x, points.x), bounds.min.y + eye_height, first(bounds.min.z, size.z, points.z)};
    return g;
}

Camera OccluderGrid::view_camera(std::uint32_t view, const Camera &lens) const
{
    const int d = int(view % std::uint32_t(directions));
    std::uint32_t p = view / std::uint32_t(directions);
    const int i = int(p % std::uint32_t(points.x));
    p /= std::uint32_t(points.x);
    const int j = int(p % std::uint32_t(points.y));
    const int k = int(p / std::uint32_t(points.y));
    Camera c = lens;
    c.position = origin + glm::vec3(float(i), float(j), float(k)) * spacing;
    c.target = c.position + heading(d, directions);
    c.up = {0.0f, 1.0f, 0.0f};
    return c;
}

std::uint32_t OccluderGrid::nearest_view(const Camera &camera) const
{
    glm::ivec3 cell;
    for (int a = 0; a < 3; ++a) {
        const float t = spacing[a] > 0.0f ? (camera.position[a] - origin[a]) / spacing[a] : 0.0f;
        cell[a] = std::clamp(int(std::lround(t)), 0, points[a] - 1);
    }
    const int d = int(std::lround(heading_angle(camera) / two_pi * float(directions))) % directions;
    const std::uint32_t point = std::uint32_t((cell.z * points.y + cell.y) * points.x + cell.x);
    return point * std::uint32_t(directions) + std::uint32_t(d);
}

bool OccluderGrid::operator==(const OccluderGrid &o) const
{
    return origin == o.origin && spacing == o.spacing && points == o.points && directions == o.directions;
}

std::vector<std::uint32_t> OccluderDatabase::occluders_for(const Camera &camera) const
{
    const std::uint32_t v = grid.nearest_view(camera);
    const std::uint32_t dirs = std::uint32_t(grid.directions);
    const std::vector<std::uint32_t> *first = nullptr;
    if (auto it = views.find(v); it != views.end()) {
        first = &it->second;
    } else {
        // A partial database: the processed view of the same heading nearest the eye.
        float best_d2 = std::numeric_limits<float>::max();
        for (const auto &[view, list] : views) {
            if (view % dirs != v % dirs)
                continue;
            const glm::vec3 p = grid.view_camera(view, camera).position - camera.position;
            if (glm::dot(p, p) < best_d2) {
                best_d2 = glm::dot(p, p);
                first = &list;
            }
        }
    }
    if (!first)
        return {};
    // The neighbouring heading on the side the camera turns to.
    const float t = heading_angle(camera) / two_pi * float(dirs) - float(v % dirs);
    const float wrapped = t > float(dirs) / 2.0f ? t - float(dirs) : t;   // heading 0 seen from just below 2 pi
    const std::uint32_t d1 = (v % dirs + (wrapped >= 0.0f ? 1 : dirs - 1)) % dirs;
    const auto second = dirs > 1 ? views.find(v - v % dirs + d1) : views.end();
    if (second == views.end())
        return *first;
    // In proportion to the turn: a camera on the heading takes its own
    // view's list first, one halfway between takes from both alike.
    const double share_b = std::min(0.5, double(std::fabs(wrapped)));
    std::vector<std::uint32_t> merged;
    const auto &a = *first, &b = second->second;
    std::size_t ia = 0, ib = 0;
    auto take = [&merged](std::uint32_t id) {
        if (std::find(merged.begin(), merged.end(), id) == merged.end())
            merged.push_back(id);
    };
    while (ia < a.size() || ib < b.size()) {
        const bool from_b = ia == a.size() || (ib < b.size() && double(ib + 1) <= share_b * double(ia + ib + 1));
        take(from_b ? b[ib++] : a[ia++]);
    }
    return merged;
}

void OccluderDatabase::save(const std::string &path) const
{
    DatabaseWriter out(path, "occluder-sets", 1, provenance);
    for (const auto &[view, list] : views) {
        out.out() << "view " << view;
        for (std::uint32_t id : list)
            out.out() << ' ' << id;
        out.out() << '\n';
    }
    out.finish();
}

OccluderDatabase OccluderDatabase::load(const std::string &path)
{
    DatabaseReader in(path, "occluder-sets", 1, "occluder database");
    in.require_algorithm("minimum-occluder-set");
    OccluderDatabase db;
    db.provenance = in.provenance();
    db.resolution = int(in.setting("resolution", 1, 65535));
    OccluderGrid &g = db.grid;
    const float max = std::numeric_limits<float>::max();
    const std::vector<double> origin = in.setting("grid-origin", 3, -max, max);
    const std::vector<double> spacing = in.setting("grid-spacing", 3, -max, max);
    const std::vector<double> points = in.setting("grid-points", 3, 1, 1e8);
    const double headings = in.setting("headings", 1, 1e8);
    g.directions = int(headings);
    if (double(g.directions) != headings)
        in.fail_at(in.settings_line(), "settings: headings wants a whole number");
    for (int a = 0; a < 3; ++a) {
        g.origin[a] = float(origin[std::size_t(a)]);
        g.spacing[a] = float(spacing[std::size_t(a)]);
        g.points[a] = int(points[std::size_t(a)]);
        if (double(g.points[a]) != points[std::size_t(a)])
            in.fail_at(in.settings_line(), "settings: grid-points wants whole numbers");
        // The last point's views stand at origin + (points - 1) * spacing.
        if (std::fabs(double(g.origin[a]) + double(g.points[a] - 1) * double(g.spacing[a])) > double(max))
            in.fail_at(in.settings_line(), "settings: the grid's points reach beyond float range along " +
                                               std::string(1, "xyz"[a]));
    }
    if (double(g.points.x) * g.points.y * g.points.z * g.directions > 1e8)
        in.fail_at(in.settings_line(), "settings: the grid has more than 1e8 views");
    while (in.next()) {
        if (in.record() != "view")
            in.fail("unknown record '" + in.record() + "' (an occluder database has view records)");
        const std::uint32_t view = std::uint32_t(in.count("the view", db.grid.view_count() - 1));
        if (db.views.count(view))
            in.fail("view " + std::to_string(view) + " repeats");
        std::vector<std::uint32_t> &list = db.views[view];
        while (in.more())
            list.push_back(std::uint32_t(in.count("an occluder", std::numeric_limits<std::uint32_t>::max())));
    }
    return db;
}

OccluderDatabase OccluderDatabase::merge(const std::vector<OccluderDatabase> &shards)
{
    if (shards.empty())
        throw std::runtime_error("merge: no shards");
    OccluderDatabase out = shards.front();
    for (std::size_t s = 1; s < shards.size(); ++s) {
        const OccluderDatabase &d = shards[s];
        if (const std::string diff = d.provenance.difference(out.provenance); !diff.empty())
            throw std::runtime_error("merge: shard " + std::to_string(s + 1) + " was made otherwise than the first: " +
                                     diff);
        for (const auto &[view, list] : d.views)
            if (!out.views.emplace(view, list).second)
                throw std::runtime_error("merge: view " + std::to_string(view) + " is in more than one shard");
    }
    return out;
}

}  // namespace occu
