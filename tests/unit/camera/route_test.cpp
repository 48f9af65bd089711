// SPDX-License-Identifier: MIT
#include "camera/route.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <fstream>
#include <stdexcept>

#include "scene/level.h"

using namespace occu;

namespace {

// A level of two leaves split by the plane x = 0: in front of it (x >= 0)
// open space, cluster 0; behind it solid, cluster -1. Two spawn points.
Level half_open_level()
{
    Level level;
    level.planes = {{{1, 0, 0}, 0.0f}};
    level.nodes = {{0, {-1, -2}, Aabb::of({-10, 0, -10}, {10, 5, 10})}};
    level.leaves = {{0, 0, Aabb::of({0, 0, -10}, {10, 5, 10}), 0, 0}, {-1, 0, Aabb::of({-10, 0, -10}, {0, 5, 10}), 0, 0}};
    LevelSpawn east, north;
    east.classname = "info_player_deathmatch";
    east.origin = {2, 1, 0};
    east.eye = {2, 1.5f, 0};
    east.direction = {1, 0, 0};
    north = east;
    north.classname = "team_CTF_redspawn";
    north.eye = {5, 1.5f, 5};
    north.direction = {0, 0, -1};   // Quake's yaw 90
    level.spawns = {east, north};
    return level;
}

}  // namespace

TEST(Route, BuiltInRoutesHaveTheFramesAsked)
{
    const Aabb city = Aabb::of({0, -1, 0}, {560, 60, 560});
    for (const char *name : {"dense", "street", "medium", "open"}) {
        const auto r = make_route(name, city, CityOptions{}, 7, 1.5f);
        ASSERT_EQ(r.size(), 7u) << name;
        EXPECT_FLOAT_EQ(r[0].aspect, 1.5f);
        EXPECT_NE(r.front().position, r.back().position) << name;
    }
    EXPECT_FLOAT_EQ(make_route("dense", city, CityOptions{}, 2, 1)[0].position.y, 1.7f);
}

TEST(Route, DenseRouteWalksTheFirstStreetTowardsTheCentre)
{
    // Buildings start 8.5 m or more from the grid's origin (half a street
    // plus an inset), as in the default city.
    const Aabb city = Aabb::of({8.5f, 0, 8.7f}, {551.5f, 60, 551.3f});
    const CityOptions options;
    for (const Camera &c : make_route("dense", city, options, 5, 1)) {
        EXPECT_FLOAT_EQ(c.position.z, options.block_size);   // on the street's centre line
        EXPECT_GE(c.position.x, 0.0f);
        EXPECT_LE(c.position.x, 2.5f * options.block_size);
        const glm::vec3 heading = c.target - c.position;
        EXPECT_GT(heading.x, 0.0f);   // towards the centre: across the blocks
        EXPECT_GT(heading.z, 0.0f);
    }
}

// The field (scene/field.h) hides nothing where every view ray descends at
// more than 24.4 degrees; the overhead route promises 26.6 at the least.
TEST(Route, OverheadRaysAllDescendSteeply)
{
    const Aabb field = Aabb::of({0, 0, 0}, {384, 1, 384});
    const auto route = make_route("overhead", field, CityOptions{}, 5, 1.0f);
    ASSERT_EQ(route.size(), 5u);
    for (const Camera &c : route) {
        const glm::mat4 inverse = glm::inverse(c.view_projection());
        float least = 90.0f;
        for (float x : {-1.0f, 0.0f, 1.0f})
            for (float y : {-1.0f, 0.0f, 1.0f}) {
                const glm::vec4 far = inverse * glm::vec4(x, y, 1.0f, 1.0f);
                const glm::vec3 ray = glm::normalize(glm::vec3(far) / far.w - c.position);
                least = std::min(least, glm::degrees(std::asin(-ray.y)));
            }
        EXPECT_GT(least, 26.5f);
        EXPECT_LT(least, 26.7f);   // the top corners: tan a = 0.5
        EXPECT_GT(c.position.y, field.max.y + 100.0f);
        EXPECT_GT(c.near_plane, 0.0f);
    }
    EXPECT_LT(route.front().position.x, route.back().position.x);
}

TEST(Route, FileRoutesAndErrorsNamingFileAndLine)
{
    // Per process: meson runs this binary once per driver, at the same time.
    const std::string path = ::testing::TempDir() + "occu_route_test_" + std::to_string(getpid()) + ".txt";
    {
        std::ofstream f(path);
        f << "# a two-camera route\n0 1.7 0  10 1.7 0\n\n5 2 5 5 2 -5  # comment\n";
    }
    const auto r = make_route(path, Aabb{}, CityOptions{}, 1, 1.0f);
    ASSERT_EQ(r.size(), 2u);
    EXPECT_FLOAT_EQ(r[1].target.z, -5.0f);
    {
        std::ofstream f(path);
        f << "0 1.7 0 10 1.7 0\n1 2 3 oops 5 6\n";
    }
    try {
        make_route(path, Aabb{}, CityOptions{}, 1, 1.0f);
        FAIL() << "no exception";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find(path + ":2"), std::string::npos) << e.what();
    }
    std::remove(path.c_str());
    EXPECT_THROW(make_route("/nonexistent/route.txt", Aabb{}, CityOptions{}, 1, 1.0f), std::runtime_error);
}

TEST(Route, OrbitCirclesTheBoundingSphereLookingAtItsCentre)
{
    const Aabb box = Aabb::of({-10, 0, -4}, {30, 8, 16});
    const auto r = make_route("orbit", box, CityOptions{}, 12, 1.0f);
    ASSERT_EQ(r.size(), 12u);
    const float radius = 0.5f * glm::length(box.extent());
    for (const Camera &c : r) {
        EXPECT_EQ(c.target, box.center());
        const float d = glm::length(c.position - box.center());
        EXPECT_GT(d, radius) << "the eye is outside the bounding sphere";
        EXPECT_GT(c.far_plane, d + radius) << "the whole sphere is inside the far plane";
        EXPECT_LT(c.near_plane, d - radius) << "nothing is nearer than the near plane";
    }
    EXPECT_NE(r[0].position, r[6].position);
}

TEST(Route, RandomRoutesAreReproducibleAndInsideTheBounds)
{
    const Aabb box = Aabb::of({-10, 0, -4}, {30, 8, 16});
    const auto a = make_route("random:25:7", box, CityOptions{}, 3, 1.0f);
    const auto b = make_route("random:25:7", box, CityOptions{}, 60, 1.0f);
    const auto c = make_route("random:25:8", box, CityOptions{}, 3, 1.0f);
    ASSERT_EQ(a.size(), 25u) << "N cameras, whatever the frame count";
    ASSERT_EQ(b.size(), 25u);
    bool differs = false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].position, b[i].position);
        EXPECT_TRUE(box.contains(a[i].position));
        const glm::vec3 view = glm::normalize(a[i].target - a[i].position);
        EXPECT_LT(std::abs(view.y), 0.9f) << "the up vector stays away from the view direction";
        differs = differs || a[i].position != c[i].position;
    }
    EXPECT_TRUE(differs) << "another seed gives other cameras";
    for (const char *bad : {"random:0:1", "random:5", "random:x:1", "random:5:1:2", "random:-3:1"})
        EXPECT_THROW(make_route(bad, box, CityOptions{}, 3, 1.0f), std::invalid_argument) << bad;
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_THROW(make_route("orbit", Aabb::of({0, 0, 0}, {inf, 1, 1}), CityOptions{}, 3, 1.0f), std::invalid_argument);
    EXPECT_THROW(make_route("orbit", Aabb{}, CityOptions{}, 3, 1.0f), std::invalid_argument);
}

namespace {
// What make_route says when it refuses a route file holding `text`, or ""
// when it reads it. The file is named per process: meson runs this binary
// once per driver, at the same time.
std::string route_file_refusal(const std::string &name, const std::string &text, std::string &path)
{
    path = ::testing::TempDir() + "occu_" + std::to_string(getpid()) + "_" + name;
    std::ofstream(path) << text;
    std::string message;
    try {
        make_route(path, Aabb{}, CityOptions{}, 1, 1.0f);
    } catch (const std::runtime_error &e) {
        message = e.what();
    }
    std::remove(path.c_str());
    return message;
}
}  // namespace

TEST(Route, FileNumbersThatAreNotFiniteAreRefusedNamingFileLineAndNumber)
{
    // nan and inf are what strtod reads; 1e39 is beyond float range, so
    // the camera's float coordinate would be infinite.
    for (const std::string bad : {"nan", "inf", "-infinity", "1e39"}) {
        SCOPED_TRACE(bad);
        std::string path;
        const std::string message =
            route_file_refusal("not-finite.route", "0 1.7 0 10 1.7 0\n0 1.7 0 " + bad + " 1.7 0\n", path);
        EXPECT_NE(message.find(path + ":2"), std::string::npos) << message;
        EXPECT_NE(message.find("tx is '" + bad + "'"), std::string::npos) << message;
        EXPECT_NE(message.find("not a finite number"), std::string::npos) << message;
    }
}

TEST(Route, RandomViewsAreTheRandomRoutesWithFieldsOfViewInTheirRange)
{
    const Aabb box = Aabb::of({-10, 0, -4}, {30, 8, 16});
    const auto route = make_route("random:40:7", box, CityOptions{}, 3, 1.0f);
    const auto views = random_views(box, 40, 7, 1.0f, 20.0f, 120.0f);
    ASSERT_EQ(views.size(), route.size());
    float least = 180.0f, most = 0.0f;
    for (std::size_t i = 0; i < views.size(); ++i) {
        EXPECT_EQ(views[i].position, route[i].position);
        EXPECT_EQ(views[i].target, route[i].target);
        EXPECT_GE(views[i].fovy_degrees, 20.0f);
        EXPECT_LE(views[i].fovy_degrees, 120.0f);
        least = std::min(least, views[i].fovy_degrees);
        most = std::max(most, views[i].fovy_degrees);
    }
    EXPECT_GT(most - least, 50.0f) << "40 draws should spread over most of the range";
    EXPECT_EQ(random_views(box, 3, 7, 1.0f, 45.0f, 45.0f)[2].fovy_degrees, 45.0f);
    EXPECT_THROW(random_views(box, 3, 7, 1.0f, 0.5f, 60.0f), std::invalid_argument);
    EXPECT_THROW(random_views(box, 3, 7, 1.0f, 60.0f, 171.0f), std::invalid_argument);
    EXPECT_THROW(random_views(box, 3, 7, 1.0f, 90.0f, 30.0f), std::invalid_argument);
    EXPECT_THROW(random_views(box, 0, 7, 1.0f, 30.0f, 90.0f), std::invalid_argument);
}

TEST(Route, FileCameraWhoseViewDirectionOverflowsIsRefused)
{
    // Each coordinate is a finite float, but target - position is not: the
    // camera's view direction, and so its view matrix, would be NaN.
    std::string path;
    const std::string message = route_file_refusal("overflow.route", "# far apart\n3e38 0 0 -3e38 0 0\n", path);
    EXPECT_NE(message.find(path + ":2"), std::string::npos) << message;
    EXPECT_NE(message.find("too far apart"), std::string::npos) << message;
}

TEST(Route, SpawnRouteTurnsAtEverySpawnPointFromItsAngle)
{
    const Level level = half_open_level();
    const Aabb box = Aabb::of({-10, 0, -10}, {10, 5, 10});
    const auto route = make_route("spawn:4", box, CityOptions{}, 1, 1.0f, &level);
    ASSERT_EQ(route.size(), 8u) << "4 views at each of the 2 spawn points, whatever the frame count";
    // East, then turning left (counter-clockwise seen from above, as Quake's
    // yaw turns): north (-z), west, south.
    const glm::vec3 turns[4] = {{1, 0, 0}, {0, 0, -1}, {-1, 0, 0}, {0, 0, 1}};
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(route[std::size_t(k)].position, level.spawns[0].eye);
        const glm::vec3 view = glm::normalize(route[std::size_t(k)].target - route[std::size_t(k)].position);
        EXPECT_NEAR(glm::length(view - turns[k]), 0.0f, 1e-5f) << "view " << k;
        EXPECT_NEAR(route[std::size_t(k)].fovy_degrees, 90.0f, 1e-3f) << "Quake's 90 degrees across a square frame";
        EXPECT_LT(route[std::size_t(k)].near_plane, 0.2f);
        EXPECT_GT(route[std::size_t(k)].far_plane, glm::length(box.extent()));
    }
    EXPECT_EQ(route[4].position, level.spawns[1].eye);
    EXPECT_NEAR(glm::length(glm::normalize(route[4].target - route[4].position) - glm::vec3(0, 0, -1)), 0.0f, 1e-5f);
    EXPECT_EQ(make_route("spawn", box, CityOptions{}, 30, 1.0f, &level).size(), 16u) << "8 views a spawn point by default";
    // A wide frame keeps the 90 degrees across: a narrower vertical field.
    EXPECT_NEAR(make_route("spawn", box, CityOptions{}, 1, 2.0f, &level)[0].fovy_degrees,
                2.0f * glm::degrees(std::atan(0.5f)), 1e-3f);
}

TEST(Route, SpawnRouteNeedsALevelWithSpawnPoints)
{
    const Aabb box = Aabb::of({-10, 0, -10}, {10, 5, 10});
    EXPECT_THROW(make_route("spawn", box, CityOptions{}, 1, 1.0f), std::invalid_argument);
    Level empty = half_open_level();
    empty.spawns.clear();
    EXPECT_THROW(make_route("spawn", box, CityOptions{}, 1, 1.0f, &empty), std::invalid_argument);
    const Level level = half_open_level();
    for (const char *bad : {"spawn:0", "spawn:x", "spawn:", "spawn:4:2", "spawn:361"})
        EXPECT_THROW(make_route(bad, box, CityOptions{}, 1, 1.0f, &level), std::invalid_argument) << bad;
}

TEST(Route, RandomEyesInALevelLieInItsOpenLeaves)
{
    const Level level = half_open_level();
    const Aabb box = Aabb::of({-10, 0, -10}, {10, 5, 10});
    const auto route = make_route("random:200:3", box, CityOptions{}, 1, 1.0f, &level);
    ASSERT_EQ(route.size(), 200u);
    for (const Camera &c : route) {
        EXPECT_GE(c.position.x, 0.0f) << "an eye in the solid half";
        EXPECT_TRUE(box.contains(c.position));
    }
    // Without the level, about half the eyes fall in the solid half.
    const auto anywhere = make_route("random:200:3", box, CityOptions{}, 1, 1.0f);
    EXPECT_GT(std::count_if(anywhere.begin(), anywhere.end(), [](const Camera &c) { return c.position.x < 0.0f; }), 50);
    // The same through random_views.
    for (const Camera &c : random_views(box, 50, 3, 1.0f, 30.0f, 90.0f, &level))
        EXPECT_GE(c.position.x, 0.0f);
    // A level all solid: refused, not an endless search.
    Level solid = level;
    solid.leaves[0].cluster = -1;
    EXPECT_THROW(make_route("random:5:3", box, CityOptions{}, 1, 1.0f, &solid), std::invalid_argument);
}

TEST(Route, OnlyRandomEyesAreUnrelatedViews)
{
    EXPECT_TRUE(unrelated_views("random:200:7"));
    for (const char *route : {"dense", "street", "medium", "open", "orbit", "overhead", "spawn", "spawn:2", "route.txt"})
        EXPECT_FALSE(unrelated_views(route)) << route;
}
