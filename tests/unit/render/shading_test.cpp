// SPDX-License-Identifier: MIT
#include "render/shading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace occu;

namespace {
float brightness(const glm::vec3 &normal)
{
    return prelit_colour(glm::vec3(1.0f), normal).r;
}
}  // namespace

TEST(Shading, RoofsWallsAndUndersidesEachGetABrightnessOfTheirOwn)
{
    // Roofs and street brightest, then the four wall orientations, the
    // undersides of ledges darkest; far enough apart to tell at a glance.
    const float order[] = {brightness({0, 1, 0}),  brightness({1, 0, 0}),  brightness({0, 0, 1}),
                           brightness({0, 0, -1}), brightness({-1, 0, 0}), brightness({0, -1, 0})};
    for (int k = 0; k + 1 < 6; ++k)
        EXPECT_GT(order[k], order[k + 1] + 0.04f) << "orientation " << k;
    EXPECT_GT(order[4], 0.5f) << "walls in shade too dark";
}

TEST(Shading, NeverClampsSoDifferentColoursStayDifferent)
{
    for (const glm::vec3 &n : {glm::vec3(0, 1, 0), glm::normalize(glm::vec3(0.13f, 0.22f, 0.05f)), glm::vec3(0, -1, 0)}) {
        const glm::vec3 c = prelit_colour(glm::vec3(1.0f, 0.98f, 0.5f), n);
        EXPECT_LE(c.r, 0.97f);
        EXPECT_LT(c.g, c.r);
        std::uint8_t a[4], b[4];
        prelit_rgba8({1.0f, 1.0f, 1.0f}, n, a);
        prelit_rgba8({0.98f, 0.98f, 0.98f}, n, b);
        EXPECT_NE(a[0], b[0]);
        EXPECT_EQ(a[3], 255);
    }
}

TEST(Shading, NotANumberGivesGrey)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::uint8_t c[4];
    prelit_rgba8({nan, 0.5f, 0.5f}, {0, 1, 0}, c);
    EXPECT_EQ(c[0], c[1]);
    EXPECT_EQ(c[1], c[2]);
    prelit_rgba8({0.5f, 0.5f, 0.5f}, {nan, nan, nan}, c);
    EXPECT_EQ(c[0], c[2]);
}

TEST(Shading, UnlitIsTheColourItself)
{
    std::uint8_t c[4];
    unlit_rgba8({0.2f, 0.6f, 1.0f}, c);
    EXPECT_EQ(c[0], 51);
    EXPECT_EQ(c[1], 153);
    EXPECT_EQ(c[2], 255);
    EXPECT_EQ(c[3], 255);
    unlit_rgba8({std::numeric_limits<float>::infinity(), 0.5f, 0.5f}, c);
    EXPECT_EQ(c[0], c[1]);
}
