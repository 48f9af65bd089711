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
    for (const char *name : {"dense", "medium", "open"}) {
        const auto r = make_route(name, city, CityOptions{}, 7, 1.5f);
        ASSERT_EQ(r.size(), 7u) << name;
        EXPECT_FLOAT_EQ(r[0].aspect, 1.5f);
        EXPECT_NE(r.front().position, r.back().position) << name;
    }
    EXPECT_FLOAT_EQ(make_route("dense", city, CityOptions{}, 2, 1)[0].position.y, 1.7f);
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
