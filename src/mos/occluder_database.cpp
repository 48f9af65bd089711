#include "mos/occluder_database.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace occu {

namespace {

constexpr float two_pi = 6.28318530718f;

glm::vec3 heading(int d, int directions)
{
    const float a = two_pi * float(d) / float(directions);
    return {std::cos(a), 0.0f, std::sin(a)};
}

}  // namespace

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
    const glm::vec3 f = camera.target - camera.position;
    float angle = std::atan2(f.z, f.x);
    if (angle < 0.0f)
        angle += two_pi;
    const int d = int(std::lround(angle / two_pi * float(directions))) % directions;
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
    const glm::vec3 f = camera.target - camera.position;
    float angle = std::atan2(f.z, f.x);
    if (angle < 0.0f)
        angle += two_pi;
    const float t = angle / two_pi * float(dirs) - float(v % dirs);
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
    std::ofstream out(path);
    if (!out)
        throw std::runtime_error(path + ": cannot write");
    out << "occu-occluder-database 1\n";
    out.precision(9);
    out << "grid " << grid.origin.x << ' ' << grid.origin.y << ' ' << grid.origin.z << ' ' << grid.spacing.x << ' '
        << grid.spacing.y << ' ' << grid.spacing.z << ' ' << grid.points.x << ' ' << grid.points.y << ' '
        << grid.points.z << ' ' << grid.directions << '\n';
    out << "scene " << scene_leaves << ' ' << scene_triangles << '\n';
    for (const auto &[view, list] : views) {
        out << "view " << view;
        for (std::uint32_t id : list)
            out << ' ' << id;
        out << '\n';
    }
    if (!out.flush())
        throw std::runtime_error(path + ": write failed");
}

OccluderDatabase OccluderDatabase::load(const std::string &path)
{
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error(path + ": cannot open occluder database");
    OccluderDatabase db;
    std::string line;
    int number = 0;
    bool header = false, have_grid = false, have_scene = false;
    auto fail = [&](const std::string &what) {
        throw std::runtime_error(path + ":" + std::to_string(number) + ": " + what);
    };
    while (std::getline(in, line)) {
        ++number;
        if (const auto hash = line.find('#'); hash != std::string::npos)
            line.erase(hash);
        std::istringstream fields(line);
        std::string key;
        if (!(fields >> key))
            continue;
        if (!header) {
            int version = 0;
            if (key != "occu-occluder-database" || !(fields >> version) || version != 1)
                fail("not an occu occluder database (expected 'occu-occluder-database 1')");
            header = true;
        } else if (key == "grid") {
            OccluderGrid &g = db.grid;
            if (!(fields >> g.origin.x >> g.origin.y >> g.origin.z >> g.spacing.x >> g.spacing.y >> g.spacing.z >>
                  g.points.x >> g.points.y >> g.points.z >> g.directions) ||
                g.points.x < 1 || g.points.y < 1 || g.points.z < 1 || g.directions < 1 ||
                double(g.points.x) * g.points.y * g.points.z * g.directions > 1e8)
                fail("grid wants OX OY OZ SX SY SZ NX NY NZ DIRECTIONS with positive counts");
            have_grid = true;
        } else if (key == "scene") {
            if (!(fields >> db.scene_leaves >> db.scene_triangles))
                fail("scene wants LEAVES TRIANGLES");
            have_scene = true;
        } else if (key == "view") {
            if (!have_grid || !have_scene)
                fail("view before grid and scene");
            std::uint32_t view = 0;
            if (!(fields >> view) || view >= db.grid.view_count())
                fail("view index missing or outside the grid");
            if (db.views.count(view))
                fail("view " + std::to_string(view) + " repeats");
            std::vector<std::uint32_t> &list = db.views[view];
            long long id = 0;
            while (fields >> id) {
                if (id < 0 || id > std::numeric_limits<std::uint32_t>::max())
                    fail("occluder id out of range");
                list.push_back(std::uint32_t(id));
            }
            if (!fields.eof())
                fail("occluder ids must be integers");
        } else {
            fail("unknown record '" + key + "'");
        }
    }
    if (!header)
        throw std::runtime_error(path + ": empty file, not an occluder database");
    if (!have_grid || !have_scene)
        throw std::runtime_error(path + ": no grid or scene record");
    return db;
}

OccluderDatabase OccluderDatabase::merge(const std::vector<OccluderDatabase> &shards)
{
    if (shards.empty())
        throw std::runtime_error("merge: no shards");
    OccluderDatabase out = shards.front();
    for (std::size_t s = 1; s < shards.size(); ++s) {
        const OccluderDatabase &d = shards[s];
        if (!(d.grid == out.grid) || d.scene_leaves != out.scene_leaves || d.scene_triangles != out.scene_triangles)
            throw std::runtime_error("merge: shard " + std::to_string(s + 1) +
                                     " was made for another grid or scene than the first");
        for (const auto &[view, list] : d.views)
            if (!out.views.emplace(view, list).second)
                throw std::runtime_error("merge: view " + std::to_string(view) + " is in more than one shard");
    }
    return out;
}

}  // namespace occu
