// SPDX-License-Identifier: MIT
#include "strategies/leone_occluder_skins/triangle_clusters.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

using namespace occu;

namespace {

// Meshes of random triangles over shared vertices, indexed in random
// order, so that a triangle's corners are far apart in its positions.
Scene random_scene(std::mt19937 &rng)
{
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), size(0.01f, 3.0f);
    Scene scene;
    for (int m = 0; m < 3; ++m) {
        Mesh mesh;
        const int vertices = 200 + 150 * m;
        for (int i = 0; i < vertices; ++i)
            mesh.positions.push_back(glm::vec3(40.0f * u(rng), 10.0f * u(rng), 40.0f * u(rng)));
        std::uniform_int_distribution<std::uint32_t> vertex(0, std::uint32_t(vertices - 1));
        for (int t = 0; t < 700 + 300 * m; ++t) {
            const std::uint32_t a = vertex(rng);
            std::uint32_t b = vertex(rng), c = vertex(rng);
            // Some small triangles: a corner's neighbours nearby.
            if (t % 3 == 0) {
                mesh.positions.push_back(mesh.positions[a] + size(rng) * glm::vec3(u(rng), u(rng), u(rng)));
                mesh.positions.push_back(mesh.positions[a] + size(rng) * glm::vec3(u(rng), u(rng), u(rng)));
                b = std::uint32_t(mesh.positions.size() - 2);
                c = std::uint32_t(mesh.positions.size() - 1);
            }
            mesh.indices.insert(mesh.indices.end(), {a, b, c});
        }
        mesh.occluder = m != 1;
        mesh.update_bounds();
        scene.meshes.push_back(std::move(mesh));
    }
    scene.update_bounds();
    return scene;
}

}  // namespace

// Every slot holds the corners the test gathered before the slots were
// laid out (hierarchy triangle, its mesh, indices and positions), bit for
// bit; a leaf's slots hold its own triangles, its clusters tile them in
// order, each at most cluster_triangles, largest first, boxed by its
// corners.
TEST(TriangleClusters, SlotsHoldEachLeafsTrianglesAndTheirCornersBitForBit)
{
    std::mt19937 rng(41);
    for (std::uint32_t leaf_triangles : {7u, 16u, 64u, 256u}) {
        const Scene scene = random_scene(rng);
        HierarchyOptions options;
        options.max_leaf_triangles = leaf_triangles;
        const Hierarchy hierarchy = Hierarchy::build(scene, options);
        const TriangleClusters clusters(scene, hierarchy);
        const auto &triangles = hierarchy.triangles();
        std::size_t slots_seen = 0;
        for (std::uint32_t node = 0; node < hierarchy.nodes().size(); ++node) {
            const HierarchyNode &n = hierarchy.nodes()[node];
            if (!n.leaf()) {
                EXPECT_EQ(clusters.begin(node), clusters.end(node));
                continue;
            }
            std::vector<std::uint32_t> held, own;
            for (std::uint32_t s = n.first_triangle; s < n.first_triangle + n.triangle_count; ++s) {
                held.push_back(clusters.triangle(s));
                own.push_back(s);
            }
            std::sort(held.begin(), held.end());
            EXPECT_EQ(held, own) << "leaf " << node;
            std::uint32_t next = 0;
            for (const TriangleClusters::Cluster *c = clusters.begin(node); c != clusters.end(node); ++c) {
                EXPECT_EQ(c->first, next);
                EXPECT_GE(c->count, 1u);
                EXPECT_LE(c->count, TriangleClusters::cluster_triangles);
                next = c->first + c->count;
                Aabb box;
                float previous_area = std::numeric_limits<float>::infinity();
                for (std::uint32_t s = n.first_triangle + c->first; s < n.first_triangle + next; ++s) {
                    const TriangleRef &t = triangles[clusters.triangle(s)];
                    const Mesh &mesh = scene.meshes[t.mesh];
                    const std::uint32_t *index = mesh.indices.data() + t.first_index;
                    const glm::vec3 gathered[3] = {mesh.positions[index[0]], mesh.positions[index[1]],
                                                   mesh.positions[index[2]]};
                    EXPECT_EQ(std::memcmp(clusters.corners(s), gathered, sizeof gathered), 0) << "slot " << s;
                    ++slots_seen;
                    const glm::vec3 *p = clusters.corners(s);
                    const float area = glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
                    EXPECT_LE(area, previous_area) << "slot " << s;
                    previous_area = area;
                    for (int i = 0; i < 3; ++i)
                        box.expand(p[i]);
                }
                EXPECT_EQ(c->box.min, box.min);
                EXPECT_EQ(c->box.max, box.max);
            }
            EXPECT_EQ(next, n.triangle_count) << "leaf " << node;
        }
        EXPECT_EQ(slots_seen, triangles.size());
    }
}
