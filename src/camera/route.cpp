// SPDX-License-Identifier: MIT
#include "camera/route.h"

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "cli/number_fields.h"
#include "scene/level.h"

namespace occu {

namespace {

// Random eyes drawn for one camera before a level is taken to have no open space.
constexpr int max_eye_tries = 100000;
// Random eyes drawn for one camera before a model is taken to have no
// inside: each costs up to 14 rays through the hierarchy, so fewer than a
// level's leaf descents; a model whose inside fills less than 1/20000 of
// its bounds has no room a camera could stand in anyway.
constexpr int max_inside_eye_tries = 20000;

bool in_open_leaf(const Level &level, const glm::vec3 &p)
{
    const std::int32_t leaf = level.leaf_at(p);
    return leaf >= 0 && level.leaves[std::size_t(leaf)].cluster >= 0;
}

std::vector<Camera> read_route_file(const std::string &path, float aspect)
{
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error("cannot read route file '" + path + "'");
    static const char *const field_names[6] = {"px", "py", "pz", "tx", "ty", "tz"};
    std::vector<Camera> route;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        line = line.substr(0, line.find('#'));
        const std::string where = path + ":" + std::to_string(number) + ": ";
        std::istringstream words(line);
        std::vector<std::string> fields;
        for (std::string word; words >> word;)
            fields.push_back(word);
        if (fields.empty())
            continue;
        if (fields.size() != 6)
            throw std::runtime_error(where + "expected six numbers \"px py pz tx ty tz\", got \"" + line + "\"");
        float numbers[6];
        for (int i = 0; i < 6; ++i)
            if (const std::string why = read_finite_float(fields[i], numbers[i]); !why.empty())
                throw std::runtime_error(where + field_names[i] + " is '" + fields[i] + "', " + why);
        Camera c;
        c.aspect = aspect;
        c.position = {numbers[0], numbers[1], numbers[2]};
        c.target = {numbers[3], numbers[4], numbers[5]};
        if (c.position == c.target)
            throw std::runtime_error(where + "position and target coincide");
        // The view matrix normalizes target - position: its squared length
        // must be a finite float, or the view direction is NaN.
        const glm::vec3 view = c.target - c.position;
        if (!std::isfinite(glm::dot(view, view)))
            throw std::runtime_error(where + "position and target are too far apart for float coordinates");
        route.push_back(c);
    }
    if (route.empty())
        throw std::runtime_error("route file '" + path + "' has no cameras");
    return route;
}

// Around the scene's bounding sphere, 1.5 radii from its centre and a
// third of a radius above it, looking at the centre: nothing is nearer
// than half a radius, so the near plane can sit a quarter radius out.
std::vector<Camera> orbit_route(const Aabb &bounds, int frames, float aspect)
{
    const glm::vec3 centre = bounds.center();
    const float radius = std::max(0.5f * glm::length(bounds.extent()), 1e-3f);
    std::vector<Camera> route;
    for (int f = 0; f < frames; ++f) {
        const float a = 6.28318530718f * float(f) / float(frames);
        Camera c;
        c.aspect = aspect;
        c.position = centre + glm::vec3(1.5f * radius * std::cos(a), radius / 3.0f, 1.5f * radius * std::sin(a));
        c.target = centre;
        c.near_plane = 0.25f * radius;
        c.far_plane = 3.0f * radius;
        route.push_back(c);
    }
    return route;
}

// Looking down at 60 degrees below the horizon, heading +z, from a height
// of 0.4 times the scene's larger ground extent above its top, across the
// scene along x (from 20% to 80% of its width), 10% into it along z. With
// the 60 degree field of view and a square frame, the top corners' rays are
// the shallowest: tan(a) = (sin 60 - t cos 60) / sqrt(t^2 + (cos 60 + t
// sin 60)^2) with t = tan 30, so a = 26.6 degrees; every ray descends at
// least that steeply (scene/field.h: why the field then hides nothing).
std::vector<Camera> overhead_route(const Aabb &bounds, int frames, float aspect)
{
    const glm::vec3 size = bounds.extent();
    const float height = std::max(0.4f * std::max(size.x, size.z), 1e-3f);
    const float pitch = glm::radians(60.0f);
    std::vector<Camera> route;
    for (int f = 0; f < frames; ++f) {
        const float t = frames == 1 ? 0.0f : float(f) / float(frames - 1);
        Camera c;
        c.aspect = aspect;
        c.position = {bounds.min.x + size.x * (0.2f + 0.6f * t), bounds.max.y + height, bounds.min.z + 0.1f * size.z};
        c.target = c.position + glm::vec3(0.0f, -std::sin(pitch), std::cos(pitch));
        // Nothing is nearer than `height`; the far plane takes in the whole scene.
        c.near_plane = 0.25f * height;
        c.far_plane = 2.0f * glm::length(size) + 2.0f * height;
        route.push_back(c);
    }
    return route;
}

// "random:N:SEED": N cameras at uniformly random points of the scene's
// bounds, each looking in a random heading and a pitch within 60 degrees
// of the horizon (the up vector stays well away from the view direction).
// The same N and SEED give the same cameras.
//
// In a Quake III level an eye is drawn again until it lies in an open leaf
// (a cluster >= 0): the level's solid space and the void around it are
// leaves of cluster -1, where no player can stand and a camera sees the
// backs of walls. In a model with an inside test (a building read from a
// file), an eye is drawn again until the test keeps it: eyes in rooms.
std::vector<Camera> random_route(const std::string &name, const Aabb &bounds, float aspect, const Level *level,
                                 const EyeTest &eye_inside)
{
    std::istringstream in(name.substr(std::string("random:").size()));
    long count = 0;
    unsigned long seed = 0;
    char colon = 0;
    if (!(in >> count >> colon >> seed) || colon != ':' || !in.eof() || count < 1 || count > 1000000)
        throw std::invalid_argument("route '" + name + "': random routes are random:N:SEED (N in 1..1000000)");
    std::mt19937 random(std::uint32_t(seed & 0xffffffffu));
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float diagonal = std::max(glm::length(bounds.extent()), 1e-3f);
    std::vector<Camera> route;
    for (long i = 0; i < count; ++i) {
        Camera c;
        c.aspect = aspect;
        c.position = bounds.min + glm::vec3(unit(random), unit(random), unit(random)) * bounds.extent();
        for (int tries = 1; level && !in_open_leaf(*level, c.position); ++tries) {
            if (tries == max_eye_tries)
                throw std::invalid_argument("route '" + name + "': no eye in the level's open space after " +
                                            std::to_string(max_eye_tries) + " random points of its bounds");
            c.position = bounds.min + glm::vec3(unit(random), unit(random), unit(random)) * bounds.extent();
        }
        for (int tries = 1; eye_inside && !eye_inside(c.position); ++tries) {
            if (tries == max_inside_eye_tries)
                throw std::invalid_argument("route '" + name + "': no eye inside the model after " +
                                            std::to_string(max_inside_eye_tries) +
                                            " random points of its bounds (a point is inside when rays in 14 "
                                            "directions from it all hit the model's triangles); the model has "
                                            "no rooms: try the orbit route");
            c.position = bounds.min + glm::vec3(unit(random), unit(random), unit(random)) * bounds.extent();
        }
        const float heading = 6.28318530718f * unit(random);
        const float pitch = glm::radians(120.0f * unit(random) - 60.0f);
        c.target = c.position + glm::vec3(std::cos(pitch) * std::cos(heading), std::sin(pitch),
                                          std::cos(pitch) * std::sin(heading));
        c.near_plane = 1e-3f * diagonal;
        c.far_plane = 2.0f * diagonal;
        route.push_back(c);
    }
    return route;
}

// "spawn" or "spawn:K" (the playable-space views): K views at each
// spawn point's eye, the first along its angle, each next turned 360 / K
// degrees to the left (counter-clockwise seen from above, as Quake's yaw
// turns), level. The lens: Quake III's default field of view (cg_fov 90,
// horizontal), its near plane (4 units), a far plane that takes in the
// whole level.
std::vector<Camera> spawn_route(const std::string &name, const Aabb &bounds, float aspect, const Level *level)
{
    long views = 8;
    if (name != "spawn") {
        std::istringstream in(name.substr(std::string("spawn:").size()));
        if (!(in >> views) || !in.eof() || views < 1 || views > 360)
            throw std::invalid_argument("route '" + name + "': spawn routes are spawn or spawn:K (K views a spawn point, 1..360)");
    }
    if (!level)
        throw std::invalid_argument("route '" + name + "': the scene is not a Quake III level; only levels have spawn points");
    if (level->spawns.empty())
        throw std::invalid_argument("route '" + name + "': the level has no spawn points (info_player_deathmatch, "
                                    "info_player_start, team_CTF_*player, team_CTF_*spawn)");
    const float fovy = 2.0f * std::atan(std::tan(glm::radians(45.0f)) / aspect);
    std::vector<Camera> route;
    for (const LevelSpawn &spawn : level->spawns)
        for (long k = 0; k < views; ++k) {
            // Turning left about +y: a yaw added in Quake turns the same way
            // in occu (the map from Quake's frame is a rotation).
            const float turn = 6.28318530718f * float(k) / float(views);
            const glm::vec3 d = spawn.direction;
            Camera c;
            c.aspect = aspect;
            c.fovy_degrees = glm::degrees(fovy);
            c.position = spawn.eye;
            c.target = spawn.eye + glm::vec3(d.x * std::cos(turn) + d.z * std::sin(turn), 0.0f,
                                             -d.x * std::sin(turn) + d.z * std::cos(turn));
            c.near_plane = 4.0f * quake3_unit_metres;
            c.far_plane = 2.0f * glm::length(bounds.extent()) + glm::length(spawn.eye - bounds.center());
            route.push_back(c);
        }
    return route;
}

}  // namespace

Camera street_level_lens(const Aabb &bounds, float aspect)
{
    Camera c;
    c.aspect = aspect;
    c.near_plane = 0.5f;
    c.far_plane = 2.0f * glm::length(bounds.extent());
    return c;
}

std::vector<Camera> make_route(const std::string &name, const Aabb &bounds, const CityOptions &city, int frames,
                               float aspect, const Level *level, const EyeTest &eye_inside)
{
    const bool built_in = name == "dense" || name == "street" || name == "medium" || name == "open" ||
                          name == "orbit" || name == "overhead" || name.rfind("random:", 0) == 0 ||
                          name == "spawn" || name.rfind("spawn:", 0) == 0;
    if (!built_in)
        return read_route_file(name, aspect);
    // Routes placed by the scene's bounds need finite ones.
    if (bounds.empty() || !std::isfinite(bounds.min.x) || !std::isfinite(bounds.min.y) ||
        !std::isfinite(bounds.min.z) || !std::isfinite(bounds.max.x) || !std::isfinite(bounds.max.y) ||
        !std::isfinite(bounds.max.z))
        throw std::invalid_argument("route '" + name + "': the scene's bounds are empty or not finite");
    if (name.rfind("random:", 0) == 0)
        return random_route(name, bounds, aspect, level, eye_inside);
    if (name == "spawn" || name.rfind("spawn:", 0) == 0)
        return spawn_route(name, bounds, aspect, level);
    if (frames < 1)
        throw std::invalid_argument("a route needs at least one frame");
    if (name == "orbit")
        return orbit_route(bounds, frames, aspect);
    if (name == "overhead")
        return overhead_route(bounds, frames, aspect);

    const glm::vec3 size = bounds.extent();
    // The street between the two middle rows of blocks.
    const float street_z = bounds.min.z + std::round(size.z / city.block_size / 2.0f) * city.block_size;
    // The city's street grid: streets run along multiples of the block size
    // from its origin, the lower left corner.
    const glm::vec2 grid_origin = glm::floor(glm::vec2(bounds.min.x, bounds.min.z) / city.block_size) * city.block_size;
    const glm::vec3 centre = bounds.center();
    std::vector<Camera> route;
    for (int f = 0; f < frames; ++f) {
        const float t = frames == 1 ? 0.0f : float(f) / float(frames - 1);
        Camera c = street_level_lens(bounds, aspect);
        if (name == "open") {
            c.position = {bounds.min.x + size.x * (0.2f + 0.6f * t), 150.0f, bounds.min.z - 0.2f * size.z};
            c.target = {bounds.min.x + 0.5f * size.x, 0.0f, bounds.min.z + 0.6f * size.z};
            c.far_plane = 2.0f * glm::length(size) + 300.0f;
            // Nothing is nearer than 100 m up here; a far near plane keeps the
            // depth buffer fine enough that distant ledges do not z-fight.
            c.near_plane = 20.0f;
        } else if (name == "dense") {
            // Poon and Wang's best case (section 6): "starts at the lower left
            // corner of the environment, and heads towards the center part".
            // At eye height along the first street inside the lower left
            // edge, from the corner crossing two and a half blocks on,
            // looking at the centre: diagonally across the blocks, so the
            // nearest buildings hide most of the city in the frustum.
            c.position = {grid_origin.x + 2.5f * city.block_size * t, 1.7f, grid_origin.y + city.block_size};
            c.target = {centre.x, 1.7f, centre.z};
        } else {
            // Along the middle street: "street" looks down it (a long open
            // sight line between facades), "medium" 35 degrees across it.
            c.position = {bounds.min.x + size.x * (0.1f + 0.8f * t), 1.7f, street_z};
            const float angle = name == "street" ? 0.0f : glm::radians(35.0f);
            c.target = c.position + glm::vec3(std::cos(angle), 0.0f, std::sin(angle));
        }
        route.push_back(c);
    }
    return route;
}

std::vector<Camera> random_views(const Aabb &bounds, long count, unsigned long seed, float aspect, float fov_min,
                                 float fov_max, const Level *level, const EyeTest &eye_inside)
{
    if (!(fov_min >= 1.0f && fov_max <= 170.0f && fov_min <= fov_max))
        throw std::invalid_argument("fields of view must lie in 1..170 degrees, the least first");
    std::vector<Camera> views = make_route("random:" + std::to_string(count) + ":" + std::to_string(seed), bounds,
                                           CityOptions{}, 1, aspect, level, eye_inside);
    std::mt19937 random(std::uint32_t(seed & 0xffffffffu) ^ 0x9e3779b9u);
    std::uniform_real_distribution<float> fov(fov_min, fov_max);
    for (Camera &c : views)
        c.fovy_degrees = fov_min == fov_max ? fov_min : fov(random);
    return views;
}

bool unrelated_views(const std::string &name)
{
    return name.rfind("random:", 0) == 0;
}

}  // namespace occu
