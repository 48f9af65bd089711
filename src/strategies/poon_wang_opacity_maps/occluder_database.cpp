#include "strategies/poon_wang_opacity_maps/occluder_database.h"

#include "preprocessing_code_hash.h"

#include "cli/number_fields.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <limits>
#include <sstream>
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

// FNV-1a: stable across runs and machines.
std::string short_hash(const std::string &text)
{
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : text) {
        h ^= c;
        h *= 1099511628211ull;
    }
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(h));
    return std::string(hex, 12);
}

}  // namespace

const char *preprocessing_code_hash()
{
    return OCCU_PREPROCESSING_CODE_HASH;
}

const char *mesa_build()
{
    return OCCU_MESA_BUILD;
}

DatabaseProvenance DatabaseProvenance::current(const Hierarchy &hierarchy, const std::string &options, int resolution)
{
    DatabaseProvenance p;
    p.code = preprocessing_code_hash();
    p.options = options;
    p.resolution = resolution;
    p.scene = hierarchy.fingerprint();
    p.leaves = std::uint32_t(hierarchy.leaf_count());
    p.triangles = hierarchy.root().subtree_triangles;
    p.mesa = mesa_build();
    return p;
}

std::string DatabaseProvenance::mismatch_for(const Hierarchy &hierarchy) const
{
    if (scene != hierarchy.fingerprint() || leaves != hierarchy.leaf_count() ||
        triangles != hierarchy.root().subtree_triangles)
        return "made for another scene or hierarchy (" + std::to_string(triangles) + " triangles in " +
               std::to_string(leaves) + " leaves, fingerprint " + scene + "; this one has " +
               std::to_string(hierarchy.root().subtree_triangles) + " in " + std::to_string(hierarchy.leaf_count()) +
               ", fingerprint " + hierarchy.fingerprint() + ")";
    if (mesa != mesa_build())
        return "made with another Mesa (" + mesa + "; this program runs on " + mesa_build() + ")";
    return {};
}

std::string DatabaseProvenance::key(const OccluderGrid &g) const
{
    std::ostringstream s;
    s.precision(9);
    s << algorithm << ' ' << code << ' ' << options << ' ' << resolution << ' ' << scene << ' ' << leaves << ' '
      << triangles << ' ' << mesa << ' ' << g.origin.x << ' ' << g.origin.y << ' ' << g.origin.z << ' '
      << g.spacing.x << ' ' << g.spacing.y << ' ' << g.spacing.z << ' ' << g.points.x << ' ' << g.points.y << ' '
      << g.points.z << ' ' << g.directions;
    return short_hash(s.str());
}

bool DatabaseProvenance::operator==(const DatabaseProvenance &o) const
{
    return algorithm == o.algorithm && code == o.code && options == o.options && resolution == o.resolution &&
           scene == o.scene && leaves == o.leaves && triangles == o.triangles && mesa == o.mesa;
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
    std::ofstream out(path);
    if (!out)
        throw std::runtime_error(path + ": cannot write");
    const DatabaseProvenance &p = provenance;
    out << "occu-occluder-database 2\n";
    out << "algorithm " << p.algorithm << ' ' << p.code << '\n';
    out << "options " << p.options << '\n';
    out << "resolution " << p.resolution << '\n';
    out << "scene " << p.scene << ' ' << p.leaves << ' ' << p.triangles << '\n';
    out << "mesa " << p.mesa << '\n';
    out.precision(9);
    out << "grid " << grid.origin.x << ' ' << grid.origin.y << ' ' << grid.origin.z << ' ' << grid.spacing.x << ' '
        << grid.spacing.y << ' ' << grid.spacing.z << ' ' << grid.points.x << ' ' << grid.points.y << ' '
        << grid.points.z << ' ' << grid.directions << '\n';
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
    bool header = false, have_grid = false;
    std::map<std::string, bool> seen;   // provenance records
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
            if (key != "occu-occluder-database" || !(fields >> version))
                fail("not an occu occluder database (expected 'occu-occluder-database 2')");
            if (version == 1)
                fail("made by an older occu-preprocess that recorded no provenance; make it again");
            if (version != 2)
                fail("occluder database version " + std::to_string(version) + ", this program reads version 2");
            header = true;
        } else if (key == "algorithm" || key == "options" || key == "resolution" || key == "scene" || key == "mesa") {
            if (seen[key])
                fail(key + " repeats");
            seen[key] = true;
            DatabaseProvenance &p = db.provenance;
            std::string rest;
            std::getline(fields >> std::ws, rest);
            std::istringstream values(rest);
            if (key == "algorithm") {
                if (!(values >> p.algorithm >> p.code) || p.algorithm != "minimum-occluder-set")
                    fail("algorithm wants 'minimum-occluder-set CODE'");
            } else if (key == "options") {
                p.options = rest;
            } else if (key == "resolution") {
                if (!(values >> p.resolution) || p.resolution < 1 || p.resolution > 65535)
                    fail("resolution wants a positive integer");
            } else if (key == "scene") {
                if (!(values >> p.scene >> p.leaves >> p.triangles))
                    fail("scene wants FINGERPRINT LEAVES TRIANGLES");
            } else if (!(values >> p.mesa)) {
                fail("mesa wants the Mesa build that made the database");
            }
        } else if (key == "grid") {
            OccluderGrid &g = db.grid;
            static const char *const coordinate_names[6] = {"OX", "OY", "OZ", "SX", "SY", "SZ"};
            std::string text;
            for (int i = 0; i < 6 && fields >> text; ++i) {
                float value = 0.0f;
                if (const std::string why = read_finite_float(text, value); !why.empty())
                    fail(std::string(coordinate_names[i]) + " is '" + text + "', " + why);
                (i < 3 ? g.origin : g.spacing)[i % 3] = value;
            }
            if (!fields || !(fields >> g.points.x >> g.points.y >> g.points.z >> g.directions) || g.points.x < 1 ||
                g.points.y < 1 || g.points.z < 1 || g.directions < 1 ||
                double(g.points.x) * g.points.y * g.points.z * g.directions > 1e8)
                fail("grid wants OX OY OZ SX SY SZ NX NY NZ DIRECTIONS with positive counts");
            // The last point's views stand at origin + (points - 1) * spacing.
            for (int a = 0; a < 3; ++a)
                if (std::fabs(double(g.origin[a]) + double(g.points[a] - 1) * double(g.spacing[a])) >
                    double(std::numeric_limits<float>::max()))
                    fail("grid points reach beyond float range along " + std::string(1, "xyz"[a]));
            have_grid = true;
        } else if (key == "view") {
            if (!have_grid)
                fail("view before grid");
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
    for (const char *record : {"algorithm", "options", "resolution", "scene", "mesa"})
        if (!seen[record])
            throw std::runtime_error(path + ": no " + std::string(record) + " record (its provenance is unknown)");
    if (!have_grid)
        throw std::runtime_error(path + ": no grid record");
    return db;
}

OccluderDatabase OccluderDatabase::merge(const std::vector<OccluderDatabase> &shards)
{
    if (shards.empty())
        throw std::runtime_error("merge: no shards");
    OccluderDatabase out = shards.front();
    for (std::size_t s = 1; s < shards.size(); ++s) {
        const OccluderDatabase &d = shards[s];
        if (!(d.grid == out.grid) || !(d.provenance == out.provenance))
            throw std::runtime_error("merge: shard " + std::to_string(s + 1) +
                                     " was made for another grid, scene, options, code or Mesa than the first");
        for (const auto &[view, list] : d.views)
            if (!out.views.emplace(view, list).second)
                throw std::runtime_error("merge: view " + std::to_string(view) + " is in more than one shard");
    }
    return out;
}

}  // namespace occu
