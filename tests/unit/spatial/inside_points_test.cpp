// SPDX-License-Identifier: MIT
#include "spatial/inside_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "camera/route.h"

using namespace occu;

namespace {

// A closed unit box (12 triangles) from (0,0,0) to (1,1,1), its hierarchy
// split into several leaves so that rays are pruned by node boxes.
Scene box_scene(bool open_top)
{
    Scene scene;
    Mesh mesh;
    append_box(mesh, Aabb::of({0, 0, 0}, {1, 1, 1}));
    if (open_top) {
        // Drop the two triangles of the +y face (every vertex at y = 1).
        std::vector<std::uint32_t> kept;
        for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
            bool top = true;
            for (int k = 0; k < 3; ++k)
                top = top && mesh.positions[mesh.indices[t + std::size_t(k)]].y == 1.0f;
            if (!top)
                kept.insert(kept.end(), mesh.indices.begin() + std::ptrdiff_t(t),
                            mesh.indices.begin() + std::ptrdiff_t(t + 3));
        }
        EXPECT_EQ(kept.size(), mesh.indices.size() - 6);
        mesh.indices = kept;
    }
    mesh.update_bounds();
    scene.meshes.push_back(mesh);
    scene.update_bounds();
    return scene;
}

HierarchyOptions small_leaves()
{
    HierarchyOptions options;
    options.max_leaf_triangles = 2;
    return options;
}

}  // namespace

TEST(InsidePoints, DirectionsAreUnitAndDistinct)
{
    for (int i = 0; i < inside_ray_directions; ++i) {
        EXPECT_NEAR(glm::length(inside_ray_direction(i)), 1.0f, 1e-6f);
        for (int j = 0; j < i; ++j)
            EXPECT_LT(glm::dot(inside_ray_direction(i), inside_ray_direction(j)), 0.99f);
    }
}

TEST(InsidePoints, ClosedBoxKeepsInsideAndRefusesOutside)
{
    const Scene scene = box_scene(false);
    const Hierarchy h = Hierarchy::build(scene, small_leaves());
    ASSERT_GT(h.nodes().size(), 1u);
    EXPECT_TRUE(inside_model(scene, h, {0.5f, 0.5f, 0.5f}));
    EXPECT_TRUE(inside_model(scene, h, {0.1f, 0.9f, 0.2f}));
    EXPECT_FALSE(inside_model(scene, h, {2.0f, 0.5f, 0.5f}));     // beside it: rays away miss
    EXPECT_FALSE(inside_model(scene, h, {0.5f, -1.0f, 0.5f}));    // below it
    EXPECT_FALSE(inside_model(scene, h, {-3.0f, -3.0f, -3.0f}));  // off a corner
}

TEST(InsidePoints, RayHitsOnlyAhead)
{
    const Scene scene = box_scene(false);
    const Hierarchy h = Hierarchy::build(scene, small_leaves());
    EXPECT_TRUE(ray_hits_model(scene, h, {-1.0f, 0.5f, 0.5f}, {1, 0, 0}));
    EXPECT_FALSE(ray_hits_model(scene, h, {-1.0f, 0.5f, 0.5f}, {-1, 0, 0}));
    EXPECT_FALSE(ray_hits_model(scene, h, {-1.0f, 2.0f, 0.5f}, {1, 0, 0}));
}

TEST(InsidePoints, OpenBoxRefusesItsInside)
{
    // Up through the missing lid nothing is hit, so even the centre is not
    // inside; the closed box's centre is (above).
    const Scene scene = box_scene(true);
    const Hierarchy h = Hierarchy::build(scene, small_leaves());
    EXPECT_FALSE(inside_model(scene, h, {0.5f, 0.5f, 0.5f}));
    EXPECT_FALSE(inside_model(scene, h, {0.5f, 0.1f, 0.5f}));
    EXPECT_TRUE(ray_hits_model(scene, h, {0.5f, 0.5f, 0.5f}, {0, -1, 0}));
}

TEST(InsidePoints, RandomRouteDrawsEyesInsideOnly)
{
    // The closed box within larger bounds: every eye the route keeps is in it.
    const Scene scene = box_scene(false);
    const Hierarchy h = Hierarchy::build(scene, small_leaves());
    const EyeTest inside = [&](const glm::vec3 &p) { return inside_model(scene, h, p); };
    const Aabb bounds = Aabb::of({-1, -1, -1}, {2, 2, 2});
    const std::vector<Camera> route = make_route("random:50:7", bounds, CityOptions{}, 1, 1.0f, nullptr, inside);
    ASSERT_EQ(route.size(), 50u);
    for (const Camera &c : route)
        EXPECT_TRUE(Aabb::of({0, 0, 0}, {1, 1, 1}).contains(c.position))
            << c.position.x << " " << c.position.y << " " << c.position.z;
}

TEST(InsidePoints, RandomRouteInAnOpenShapeIsAClearError)
{
    const Scene scene = box_scene(true);
    const Hierarchy h = Hierarchy::build(scene, small_leaves());
    long tests = 0;
    const EyeTest inside = [&](const glm::vec3 &p) {
        ++tests;
        return inside_model(scene, h, p);
    };
    try {
        make_route("random:3:1", scene.bounds, CityOptions{}, 1, 1.0f, nullptr, inside);
        FAIL() << "an open box has no inside point, yet the route found eyes";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("no eye inside the model"), std::string::npos) << e.what();
    }
    EXPECT_GT(tests, 1000);      // it did try
    EXPECT_LE(tests, 20000);     // and gave up after a bounded number of candidates
}
