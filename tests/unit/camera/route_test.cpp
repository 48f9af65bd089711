#include "camera/route.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

using namespace occu;

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
