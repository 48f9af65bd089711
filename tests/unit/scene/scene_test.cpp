// SPDX-License-Identifier: MIT
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "scene/city.h"
#include "scene/palette.h"

using namespace occu;

TEST(AppendBox, TwelveTrianglesWoundOutwards)
{
    Mesh m;
    const Aabb box = Aabb::of({-1, 2, 3}, {4, 5, 9});
    append_box(m, box);
    ASSERT_EQ(m.triangle_count(), 12u);
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
        const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                        c = m.positions[m.indices[t + 2]];
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        // Counter-clockwise seen from outside: the winding's normal is the outward one.
        EXPECT_NEAR(glm::dot(n, m.normals[m.indices[t]]), 1.0f, 1e-6f) << "triangle " << t / 3;
        EXPECT_GT(glm::dot(n, a - box.center()), 0.0f) << "triangle " << t / 3;
    }
    EXPECT_EQ(m.bounds.min, box.min);
    EXPECT_EQ(m.bounds.max, box.max);
}

namespace {
// Two meshes of one box each; the second is called "roof".
Scene two_boxes()
{
    Scene s;
    s.meshes.resize(2);
    append_box(s.meshes[0], Aabb::of({0, 0, 0}, {1, 1, 1}));
    append_box(s.meshes[1], Aabb::of({0, 1, 0}, {1, 2, 1}));
    s.meshes[1].name = "roof";
    s.update_bounds();
    return s;
}

std::string refusal_of(const Scene &scene)
{
    try {
        require_finite_vertices(scene, "scene 'house.obj'");
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(RequireFiniteVertices, NanCoordinateIsRefusedNamingSourceMeshAndVertex)
{
    Scene s = two_boxes();
    s.meshes[1].positions[5].y = std::numeric_limits<float>::quiet_NaN();
    const std::string message = refusal_of(s);
    EXPECT_NE(message.find("house.obj"), std::string::npos) << message;
    EXPECT_NE(message.find("'roof'"), std::string::npos) << message;
    EXPECT_NE(message.find("vertex 5"), std::string::npos) << message;
    EXPECT_NE(message.find("not finite"), std::string::npos) << message;
}

TEST(RequireFiniteVertices, InfiniteCoordinatesAreRefusedWithTheirCount)
{
    Scene s = two_boxes();
    s.meshes[0].positions[2].x = std::numeric_limits<float>::infinity();
    s.meshes[0].positions[7].z = -std::numeric_limits<float>::infinity();
    const std::string message = refusal_of(s);
    EXPECT_NE(message.find("vertex 2"), std::string::npos) << message;
    EXPECT_NE(message.find("inf"), std::string::npos) << message;
    EXPECT_NE(message.find("2 of 24 vertices"), std::string::npos) << message;
}

TEST(RequireFiniteVertices, FiniteSceneIsAccepted)
{
    EXPECT_EQ(refusal_of(two_boxes()), "");
}

TEST(City, DefaultIsAbout300kTrianglesAndDeterministic)
{
    const Scene a = generate_city({});
    const Scene b = generate_city({});
    EXPECT_GT(a.triangle_count(), 250000u);
    EXPECT_LT(a.triangle_count(), 350000u);
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    EXPECT_EQ(a.meshes[17].positions, b.meshes[17].positions);
    // Streets at street level: the ground's top is y = 0 and buildings stand on it.
    EXPECT_FLOAT_EQ(a.bounds.min.y, -1.0f);
    EXPECT_GT(a.bounds.max.y, 20.0f);
}

TEST(City, CopiesMultiplyTheGrid)
{
    CityOptions small;
    small.blocks_x = small.blocks_z = 2;
    CityOptions copied = small;
    copied.copies = 3;
    const Scene one = generate_city(small), nine = generate_city(copied);
    // Nine copies of the buildings, one ground.
    EXPECT_EQ(nine.triangle_count() - 12, 9 * (one.triangle_count() - 12));
    EXPECT_NEAR(nine.bounds.extent().x, 3 * one.bounds.extent().x, 1e-3f);
}

TEST(City, OtherSeedOtherCity)
{
    CityOptions a, b;
    b.seed = 7;
    EXPECT_NE(generate_city(a).triangle_count(), generate_city(b).triangle_count());
}

TEST(City, BuildingsHaveHuesOfTheirOwnAndWallsLedgesAndRoofsApart)
{
    const Scene city = generate_city({});
    // The palette draws from a generator of its own: the shapes are the
    // city of 272,796 triangles that docs/walkthrough.md describes.
    EXPECT_EQ(city.triangle_count(), 272796u);
    std::size_t buildings = 0;
    const Mesh *before = nullptr;
    for (const Mesh &m : city.meshes) {
        if (m.name == "ground")
            continue;
        ++buildings;
        ASSERT_EQ(m.colors.size(), m.positions.size());
        // The body's box comes first: 4 vertices per face, -x +x -y +y -z +z;
        // its top (the roof), a wall's top edge, a ledge (after the body).
        const glm::vec3 roof = m.colors[12], wall = m.colors[4 * 4 + 2], ledge = m.colors[24];
        EXPECT_EQ(m.normals[12], glm::vec3(0, 1, 0));
        EXPECT_NE(roof, wall);
        EXPECT_NE(ledge, wall);
        EXPECT_GT(luminance(wall), 0.3f) << "a dark facade";
        // Street level a little darker than the top of the wall.
        EXPECT_LT(luminance(m.colors[4 * 4 + 0]), luminance(wall));
        if (before) {
            EXPECT_NE(before->colors[4 * 4 + 2], wall) << "two neighbours of one hue";
        }
        before = &m;
    }
    EXPECT_GT(buildings, 100u);
}
