// SPDX-License-Identifier: MIT
// Occluder skins (Leone et al., section 4): skins lie inside their meshes
// (checked by brute-force ray parity and, for convex meshes, by the face
// planes), fill simple ones, stay out of concavities, courtyards and sealed
// cavities, leaky meshes are reported and get none, the two thresholds stop
// the search where they should, the densest start beats the first where
// it matters; the skin database round-trips, refuses bad lines naming file
// and line, and its shards merge to the whole.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>

#include "occluders/occluder_skins.h"
#include "scene/city.h"
#include "scene/scene.h"

using namespace occu;

namespace {

Mesh box_mesh(const Aabb &box, const std::string &name = "box")
{
    Mesh m;
    m.name = name;
    append_box(m, box);
    m.update_bounds();
    return m;
}

// A closed mesh of unit cells: the cells' faces that no other cell covers,
// counter-clockwise from outside. Any set of cells gives a watertight
// surface without inner faces: concave shapes, courtyards, cavities.
Mesh cells_mesh(const std::vector<glm::ivec3> &cells, float size, const glm::vec3 &origin = glm::vec3(0.0f))
{
    std::set<std::tuple<int, int, int>> occupied;
    for (const glm::ivec3 &c : cells)
        occupied.insert({c.x, c.y, c.z});
    auto has = [&](const glm::ivec3 &c) { return occupied.count({c.x, c.y, c.z}) > 0; };
    Mesh m;
    m.name = "cells";
    for (const glm::ivec3 &c : cells)
        for (int a = 0; a < 3; ++a)
            for (int side = 0; side < 2; ++side) {
                glm::ivec3 step(0);
                step[a] = side ? 1 : -1;
                if (has(c + step))
                    continue;
                const int b = (a + 1) % 3, d = (a + 2) % 3;
                glm::vec3 base = origin + glm::vec3(c) * size, eb(0.0f), ed(0.0f);
                base[a] += side ? size : 0.0f;
                eb[b] = size;
                ed[d] = size;
                // eb x ed points along +a: this order faces +a, its reverse -a.
                glm::vec3 quad[4] = {base, base + eb, base + eb + ed, base + ed};
                if (!side)
                    std::swap(quad[1], quad[3]);
                const auto first = std::uint32_t(m.positions.size());
                for (const glm::vec3 &p : quad) {
                    m.positions.push_back(p);
                    m.normals.push_back(glm::vec3(step));
                }
                m.indices.insert(m.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
            }
    m.update_bounds();
    return m;
}

std::vector<glm::ivec3> cell_block(const glm::ivec3 &lo, const glm::ivec3 &hi)   // hi exclusive
{
    std::vector<glm::ivec3> cells;
    for (int z = lo.z; z < hi.z; ++z)
        for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x)
                cells.push_back({x, y, z});
    return cells;
}

// Ray parity, by brute force: crossings of the ray from p along d with the
// mesh's triangles (Möller and Trumbore's ray/triangle intersection).
int crossings(const Mesh &mesh, const glm::dvec3 &p, const glm::dvec3 &d)
{
    int count = 0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
            c(mesh.positions[mesh.indices[3 * t + 2]]);
        const glm::dvec3 e1 = b - a, e2 = c - a, q = glm::cross(d, e2);
        const double det = glm::dot(e1, q);
        if (std::fabs(det) < 1e-14)
            continue;   // parallel to the triangle
        const glm::dvec3 s = p - a;
        const double u = glm::dot(s, q) / det;
        if (u < 0.0 || u > 1.0)
            continue;
        const glm::dvec3 r = glm::cross(s, e1);
        const double v = glm::dot(d, r) / det;
        if (v < 0.0 || u + v > 1.0)
            continue;
        if (glm::dot(e2, r) / det > 0.0)
            ++count;
    }
    return count;
}

// Inside by parity of a ray in a random direction that is along no axis.
bool inside_by_parity(const Mesh &mesh, const glm::vec3 &p, std::mt19937 &rng)
{
    std::normal_distribution<double> normal;
    glm::dvec3 d;
    do
        d = glm::dvec3(normal(rng), normal(rng), normal(rng));
    while (std::fabs(d.x) < 0.1 || std::fabs(d.y) < 0.1 || std::fabs(d.z) < 0.1);
    return crossings(mesh, glm::dvec3(p), glm::normalize(d)) % 2 == 1;
}

// How many of `samples` random points of `box` (its corners among them,
// pulled in by a micrometre) are outside `mesh` by ray parity.
int points_outside(const Mesh &mesh, const Aabb &box, int samples, std::mt19937 &rng)
{
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int outside = 0;
    for (int i = 0; i < samples; ++i) {
        glm::vec3 t = i < 8 ? glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1) : glm::vec3(unit(rng), unit(rng), unit(rng));
        t = glm::clamp(t, glm::vec3(1e-6f), glm::vec3(1.0f - 1e-6f));
        if (!inside_by_parity(mesh, box.min + t * box.extent(), rng))
            ++outside;
    }
    return outside;
}

bool within(const Aabb &inner, const Aabb &outer)
{
    return glm::all(glm::greaterThanEqual(inner.min, outer.min)) && glm::all(glm::lessThanEqual(inner.max, outer.max));
}

// The volume two boxes share (0 when they only touch).
float shared_volume(const Aabb &a, const Aabb &b)
{
    const glm::vec3 e = glm::max(glm::min(a.max, b.max) - glm::max(a.min, b.min), glm::vec3(0.0f));
    return e.x * e.y * e.z;
}

float volume(const Aabb &b)
{
    const glm::vec3 e = b.extent();
    return e.x * e.y * e.z;
}

std::vector<Aabb> skins_of(const Mesh &mesh, const SkinOptions &options = {})
{
    std::string why;
    const auto skins = occluder_skins(mesh, options, &why);
    EXPECT_TRUE(skins.has_value()) << why;
    return skins.value_or(std::vector<Aabb>{});
}

// A U (in x and z, open towards +z), three cells high, of 2 m cells: the
// gap between its arms, x in [4, 6], z in [4, 10], is outside.
Mesh u_mesh()
{
    std::vector<glm::ivec3> cells;
    for (const glm::ivec3 &c : cell_block({0, 0, 0}, {5, 3, 5}))
        if (!(c.x == 2 && c.z >= 2))
            cells.push_back(c);
    return cells_mesh(cells, 2.0f);
}

}  // namespace

TEST(OccluderSkins, OptionsDescribeThemselvesAndBadOnesAreRefused)
{
    SkinOptions o;
    EXPECT_EQ(o.describe(), "voxel=0.5 max-boxes=8 min-volume=1 start=densest");
    o.start = SkinOptions::Start::first;
    o.voxel_size = 0.25f;
    EXPECT_EQ(o.describe(), "voxel=0.25 max-boxes=8 min-volume=1 start=first");
    EXPECT_TRUE(o.problem().empty());
    const Mesh box = box_mesh(Aabb::of({0, 0, 0}, {4, 4, 4}));
    for (float bad : {0.0f, -1.0f, NAN, INFINITY}) {
        SkinOptions b;
        b.voxel_size = bad;
        EXPECT_FALSE(b.problem().empty()) << bad;
        EXPECT_THROW(occluder_skins(box, b), std::invalid_argument) << bad;
    }
    SkinOptions no_boxes;
    no_boxes.max_boxes = 0;
    EXPECT_THROW(occluder_skins(box, no_boxes), std::invalid_argument);
    SkinOptions negative;
    negative.min_volume = -1.0f;
    EXPECT_THROW(occluder_skins(box, negative), std::invalid_argument);
}

TEST(OccluderSkins, BoxMeshGivesOneSkinFillingItToWithinAVoxel)
{
    const Aabb box = Aabb::of({0.3f, 1.1f, -2.0f}, {10.6f, 7.45f, 9.9f});
    SkinOptions o;
    const std::vector<Aabb> skins = skins_of(box_mesh(box), o);
    ASSERT_EQ(skins.size(), 1u);
    const Aabb &s = skins.front();
    EXPECT_TRUE(within(s, box)) << "skin pokes out of the box";
    for (int a = 0; a < 3; ++a) {
        EXPECT_GT(s.min[a] - box.min[a], 0.0f) << "axis " << a;   // the surface voxels come first
        EXPECT_LE(s.min[a] - box.min[a], o.voxel_size) << "axis " << a;
        EXPECT_GT(box.max[a] - s.max[a], 0.0f) << "axis " << a;
        EXPECT_LE(box.max[a] - s.max[a], o.voxel_size) << "axis " << a;
    }
    // Whole voxels.
    for (int a = 0; a < 3; ++a) {
        const float voxels = s.extent()[a] / o.voxel_size;
        EXPECT_NEAR(voxels, std::round(voxels), 1e-3f) << "axis " << a;
    }
}

TEST(OccluderSkins, SmallCityBuildingsAreWatertightAndSkinsLieInsideTheirBodies)
{
    CityOptions city;
    city.blocks_x = city.blocks_z = 1;
    const Scene scene = generate_city(city);
    const SkinOptions options;
    const SceneSkins all = scene_skins(scene, options);
    for (const SkinReport &r : all.skipped)
        ADD_FAILURE() << r.message();
    ASSERT_EQ(all.skins.size(), scene.meshes.size());
    std::mt19937 rng(7);
    for (const MeshSkins &m : all.skins) {
        const Mesh &mesh = scene.meshes[m.mesh];
        ASSERT_FALSE(m.boxes.empty()) << "mesh " << m.mesh;
        // The body is the building's first box (scene/city.cpp): 24 corners.
        Aabb body;
        for (std::size_t i = 0; i < 24; ++i)
            body.expand(mesh.positions[i]);
        float skin_volume = 0.0f;
        for (const Aabb &b : m.boxes) {
            EXPECT_TRUE(within(b, body)) << "mesh " << m.mesh << ": a skin pokes out of the body";
            EXPECT_EQ(points_outside(mesh, b, 200, rng), 0) << "mesh " << m.mesh;
            skin_volume += volume(b);
        }
        // Conservative but not timid: most of the body (ledges are outside it).
        if (mesh.name != "ground") {
            EXPECT_GT(skin_volume, 0.75f * volume(body)) << "mesh " << m.mesh;
        }
    }
}

bool same_boxes(const std::vector<Aabb> &a, const std::vector<Aabb> &b)
{
    if (a.size() != b.size())
        return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].min != b[i].min || a[i].max != b[i].max)
            return false;
    return true;
}

// The copies of the city's grid are its buildings moved without turning:
// each copy gets its first copy's skins moved with it, never reaching out
// of its own body (each corner rounded inwards), and a mesh that is a copy
// but for one vertex moved by more than the voxel test's tolerance gets
// skins of its own, as occluder_skins makes them.
TEST(OccluderSkins, CopiesOfAMeshGetItsSkinsMovedInsideTheirOwnBodies)
{
    CityOptions city;
    city.blocks_x = city.blocks_z = 1;
    city.copies = 2;
    Scene scene = generate_city(city);
    const std::size_t per_copy = (scene.meshes.size() - 1) / 4;   // the ground is one mesh for all copies
    ASSERT_EQ(scene.meshes.size(), 4 * per_copy + 1);
    // The last building of the last copy, one vertex moved 1 mm.
    std::uint32_t bent_index = std::uint32_t(scene.meshes.size() - 1);
    while (scene.meshes[bent_index].name == "ground")
        --bent_index;
    scene.meshes[bent_index].positions[0].y += 1e-3f;
    const SkinOptions options;
    const SceneSkins all = scene_skins(scene, options);
    for (const SkinReport &r : all.skipped)
        ADD_FAILURE() << r.message();
    std::map<std::uint32_t, const MeshSkins *> by_mesh;
    for (const MeshSkins &m : all.skins)
        by_mesh[m.mesh] = &m;
    std::mt19937 rng(11);
    std::size_t moved = 0;
    for (const MeshSkins &m : all.skins) {
        const Mesh &mesh = scene.meshes[m.mesh];
        if (mesh.name == "ground")
            continue;
        Aabb body;
        for (std::size_t i = 0; i < 24; ++i)
            body.expand(mesh.positions[i]);
        for (const Aabb &b : m.boxes) {
            EXPECT_TRUE(within(b, body)) << "mesh " << m.mesh << ": a skin pokes out of the body";
            EXPECT_EQ(points_outside(mesh, b, 200, rng), 0) << "mesh " << m.mesh;
        }
        if (m.mesh == bent_index) {
            EXPECT_TRUE(same_boxes(m.boxes, skins_of(mesh, options))) << "the bent copy's skins are not its own";
            continue;
        }
        // The first copy's mesh of the same shape: its skins moved by the
        // difference of their first vertices, to within a float step.
        for (const auto &[index, first] : by_mesh) {
            const Mesh &f = scene.meshes[index];
            if (index >= m.mesh || f.indices != mesh.indices || f.positions.size() != mesh.positions.size())
                continue;
            const glm::dvec3 by = glm::dvec3(mesh.positions[0]) - glm::dvec3(f.positions[0]);
            if (glm::length(glm::dvec3(mesh.positions[5]) - glm::dvec3(f.positions[5]) - by) > 1e-3)
                continue;
            ASSERT_EQ(first->boxes.size(), m.boxes.size()) << "mesh " << m.mesh << " of mesh " << index;
            for (std::size_t b = 0; b < m.boxes.size(); ++b)
                for (int a = 0; a < 3; ++a) {
                    const double step = 4.0 * std::abs(by[a] + double(first->boxes[b].max[a])) * 6e-8;
                    EXPECT_NEAR(double(m.boxes[b].min[a]), double(first->boxes[b].min[a]) + by[a], step);
                    EXPECT_NEAR(double(m.boxes[b].max[a]), double(first->boxes[b].max[a]) + by[a], step);
                }
            ++moved;
            break;
        }
    }
    EXPECT_EQ(moved, 3 * per_copy - 1) << "every later copy's building but the bent one";
    // Shards give every mesh the same skins.
    const SceneSkins odd = scene_skins(scene, options, 2, 2);
    for (const MeshSkins &m : odd.skins)
        EXPECT_TRUE(same_boxes(m.boxes, by_mesh.at(m.mesh)->boxes)) << "mesh " << m.mesh;
}

TEST(OccluderSkins, RotatedCubeSkinsLieInsideEveryFacePlane)
{
    // Faces along no axis exercise all of the separating-axis test.
    Mesh cube = box_mesh(Aabb::of({-3, -3, -3}, {3, 3, 3}));
    const glm::mat3 rotate = glm::mat3(glm::vec3(0.36f, 0.48f, -0.8f), glm::vec3(-0.8f, 0.6f, 0.0f),
                                       glm::vec3(0.48f, 0.64f, 0.6f));   // orthonormal
    for (glm::vec3 &p : cube.positions)
        p = rotate * p + glm::vec3(10.0f, 2.0f, -5.0f);
    cube.update_bounds();
    const std::vector<Aabb> skins = skins_of(cube);
    ASSERT_FALSE(skins.empty());
    float skin_volume = 0.0f;
    for (const Aabb &b : skins) {
        skin_volume += volume(b);
        for (int c = 0; c < 8; ++c)
            for (std::size_t t = 0; t < cube.triangle_count(); ++t) {
                const glm::dvec3 a(cube.positions[cube.indices[3 * t]]), p1(cube.positions[cube.indices[3 * t + 1]]),
                    p2(cube.positions[cube.indices[3 * t + 2]]);
                const glm::dvec3 n = glm::cross(p1 - a, p2 - a);   // outward
                EXPECT_LT(glm::dot(n, glm::dvec3(b.corner(c)) - a), 0.0) << "corner " << c << " beyond face " << t;
            }
    }
    // Turned like this, the cube (216 m^3) holds a first box of 28 m^3 and
    // seven of 75 m^3 in all at 0.5 m voxels.
    EXPECT_GT(volume(skins.front()), 20.0f);
    EXPECT_GT(skin_volume, 60.0f);
    EXPECT_LT(skin_volume, 216.0f);
}

TEST(OccluderSkins, ConcaveMeshGivesSeveralBoxesThatNeverCoverTheConcavity)
{
    const Mesh u = u_mesh();
    const std::vector<Aabb> skins = skins_of(u);
    EXPECT_GT(skins.size(), 1u);
    const Aabb gap = Aabb::of({4.0f, -1.0f, 4.0f}, {6.0f, 7.0f, 10.0f});
    std::mt19937 rng(11);
    float skin_volume = 0.0f;
    for (const Aabb &b : skins) {
        EXPECT_EQ(shared_volume(b, gap), 0.0f) << "a skin covers the U's gap";
        EXPECT_EQ(points_outside(u, b, 200, rng), 0);
        skin_volume += volume(b);
    }
    EXPECT_GT(skin_volume, 0.5f * 22 * 3 * 8);

    // A ring of buildings round a courtyard (the city's blocks, in one mesh).
    std::vector<glm::ivec3> ring;
    for (const glm::ivec3 &c : cell_block({0, 0, 0}, {6, 4, 6}))
        if (c.x == 0 || c.z == 0 || c.x == 5 || c.z == 5)
            ring.push_back(c);
    const Mesh courtyard = cells_mesh(ring, 2.0f);
    const std::vector<Aabb> ring_skins = skins_of(courtyard);
    EXPECT_GE(ring_skins.size(), 4u);
    const Aabb yard = Aabb::of({2.0f, -1.0f, 2.0f}, {10.0f, 9.0f, 10.0f});
    for (const Aabb &b : ring_skins) {
        EXPECT_EQ(shared_volume(b, yard), 0.0f) << "a skin covers the courtyard";
        EXPECT_EQ(points_outside(courtyard, b, 100, rng), 0);
    }
}

TEST(OccluderSkins, FacesOnVoxelBoundariesMarkTheVoxelsTheyTouch)
{
    // A 10 m cube of 0.25 m cells with a notch 0.5 m wide cut down from its
    // top. The grid is centred on the mesh's box (occluder_skins.cpp), so
    // at 0.5 m voxels its boundaries lie at 0.25 + 0.5 k: the notch's walls,
    // x = 4.75 and 5.25, lie on them, and the notch is one voxel wide. Were
    // the voxels a face only touches not surface voxels, the interior would
    // flow into the notch (and out of the mesh).
    std::vector<glm::ivec3> cells;
    for (const glm::ivec3 &c : cell_block({0, 0, 0}, {40, 40, 40}))
        if (!(c.x >= 19 && c.x < 21 && c.y >= 30))
            cells.push_back(c);
    const Mesh notched = cells_mesh(cells, 0.25f);
    const std::vector<Aabb> skins = skins_of(notched);
    ASSERT_GE(skins.size(), 2u);
    const Aabb notch = Aabb::of({4.75f, 7.5f, -1.0f}, {5.25f, 11.0f, 11.0f});
    std::mt19937 rng(19);
    for (const Aabb &b : skins) {
        EXPECT_EQ(shared_volume(b, notch), 0.0f) << "a skin fills the notch";
        EXPECT_EQ(points_outside(notched, b, 50, rng), 0);
    }
}

TEST(OccluderSkins, SealedCavityAndCourtyardBehindANarrowSlitStayEmpty)
{
    // A hollow cube: walls of one 2 m cell round a 6 m cavity. The cavity's
    // voxels see surface in all six directions and its flood is sealed, as
    // for an interior; its winding number (0) tells it is outside.
    std::vector<glm::ivec3> shell;
    for (const glm::ivec3 &c : cell_block({0, 0, 0}, {5, 5, 5}))
        if (c.x == 0 || c.y == 0 || c.z == 0 || c.x == 4 || c.y == 4 || c.z == 4)
            shell.push_back(c);
    const Mesh hollow = cells_mesh(shell, 2.0f);
    const std::vector<Aabb> skins = skins_of(hollow);
    EXPECT_FALSE(skins.empty());
    const Aabb cavity = Aabb::of({2.0f, 2.0f, 2.0f}, {8.0f, 8.0f, 8.0f});
    std::mt19937 rng(13);
    for (const Aabb &b : skins) {
        EXPECT_EQ(shared_volume(b, cavity), 0.0f) << "a skin fills the cavity";
        EXPECT_EQ(points_outside(hollow, b, 100, rng), 0);
    }

    // A roofed courtyard open to the outside through a slit of 0.3 m, less
    // than a voxel: the flood cannot get out, but it is outside all the same.
    std::vector<glm::ivec3> roofed;
    for (const glm::ivec3 &c : cell_block({0, 0, 0}, {20, 20, 20})) {
        const bool wall = c.x < 3 || c.y < 3 || c.z < 3 || c.x >= 17 || c.y >= 17 || c.z >= 17;
        const bool slit = c.x < 3 && c.y == 10 && c.z == 10;
        if (wall && !slit)
            roofed.push_back(c);
    }
    const Mesh slit = cells_mesh(roofed, 0.3f);
    const std::vector<Aabb> slit_skins = skins_of(slit);
    const Aabb yard = Aabb::of({0.9f, 0.9f, 0.9f}, {5.1f, 5.1f, 5.1f});
    for (const Aabb &b : slit_skins) {
        EXPECT_EQ(shared_volume(b, yard), 0.0f) << "a skin fills the courtyard behind the slit";
        EXPECT_EQ(points_outside(slit, b, 50, rng), 0);
    }
}

TEST(OccluderSkins, RoomWithADoorIsWatertightAndStaysEmpty)
{
    // A hollow cube of 2 m cells with a door through one wall: most of the
    // room sees walls in all six directions, and its flood goes out through
    // the door, yet the mesh is closed: the room is outside, not a leak.
    std::vector<glm::ivec3> walls;
    for (const glm::ivec3 &c : cell_block({0, 0, 0}, {5, 5, 5}))
        if ((c.x == 0 || c.y == 0 || c.z == 0 || c.x == 4 || c.y == 4 || c.z == 4) && !(c.x == 0 && c.y == 1 && c.z == 1))
            walls.push_back(c);
    const Mesh room = cells_mesh(walls, 2.0f);
    const std::vector<Aabb> skins = skins_of(room);
    EXPECT_GE(skins.size(), 6u);
    const Aabb inside = Aabb::of({2.0f, 2.0f, 2.0f}, {8.0f, 8.0f, 8.0f}), door = Aabb::of({-1.0f, 2.0f, 2.0f}, {2.0f, 4.0f, 4.0f});
    std::mt19937 rng(23);
    for (const Aabb &b : skins) {
        EXPECT_EQ(shared_volume(b, inside), 0.0f) << "a skin fills the room";
        EXPECT_EQ(shared_volume(b, door), 0.0f) << "a skin fills the door";
        EXPECT_EQ(points_outside(room, b, 50, rng), 0);
    }
}

TEST(OccluderSkins, MeshWithAFaceRemovedIsReportedNotWatertight)
{
    // One triangle missing: the flood leaks out through it.
    Mesh leaky = box_mesh(Aabb::of({0, 0, 0}, {8, 6, 10}), "leaky");
    leaky.indices.resize(leaky.indices.size() - 3);
    std::string why;
    EXPECT_FALSE(occluder_skins(leaky, SkinOptions{}, &why).has_value());
    EXPECT_NE(why.find("not watertight"), std::string::npos) << why;

    // A whole side missing: no voxel sees surface in all six directions,
    // and the winding number inside is not whole.
    Mesh open = box_mesh(Aabb::of({0, 0, 0}, {8, 6, 10}), "open");
    open.indices.resize(open.indices.size() - 6);
    why.clear();
    EXPECT_FALSE(occluder_skins(open, SkinOptions{}, &why).has_value());
    EXPECT_NE(why.find("not watertight"), std::string::npos) << why;

    // A hole narrower than a voxel: the flood stays in, the winding number tells.
    std::vector<glm::ivec3> cells = cell_block({0, 0, 0}, {20, 20, 20});
    Mesh pierced = cells_mesh(cells, 0.25f);
    // Drop the two triangles of one 0.25 m face in the middle of the top.
    for (std::size_t t = 0; t + 1 < pierced.triangle_count(); t += 2) {
        const glm::vec3 c = (pierced.positions[pierced.indices[3 * t]] + pierced.positions[pierced.indices[3 * t + 2]]) * 0.5f;
        if (std::fabs(c.y - 5.0f) < 1e-4f && std::fabs(c.x - 2.625f) < 1e-4f && std::fabs(c.z - 2.625f) < 1e-4f) {
            pierced.indices.erase(pierced.indices.begin() + std::ptrdiff_t(3 * t), pierced.indices.begin() + std::ptrdiff_t(3 * t + 6));
            break;
        }
    }
    ASSERT_EQ(pierced.triangle_count(), 20u * 20u * 6u * 2u - 2u);
    why.clear();
    EXPECT_FALSE(occluder_skins(pierced, SkinOptions{}, &why).has_value());
    EXPECT_NE(why.find("not watertight"), std::string::npos) << why;
    EXPECT_NE(why.find("winding"), std::string::npos) << why;

    // In a scene: reported by index and name, no skins.
    Scene scene;
    scene.meshes.push_back(box_mesh(Aabb::of({20, 0, 0}, {28, 6, 10}), "solid"));
    scene.meshes.push_back(leaky);
    scene.update_bounds();
    const SceneSkins s = scene_skins(scene, SkinOptions{});
    ASSERT_EQ(s.skins.size(), 1u);
    EXPECT_EQ(s.skins[0].mesh, 0u);
    ASSERT_EQ(s.skipped.size(), 1u);
    EXPECT_EQ(s.skipped[0].mesh, 1u);
    EXPECT_NE(s.skipped[0].message().find("mesh 1 'leaky': not watertight"), std::string::npos)
        << s.skipped[0].message();
}

TEST(OccluderSkins, ThinMeshHasNoInterior)
{
    std::string why;
    EXPECT_FALSE(occluder_skins(box_mesh(Aabb::of({0, 0, 0}, {10, 0.6f, 10})), SkinOptions{}, &why).has_value());
    EXPECT_NE(why.find("no interior"), std::string::npos) << why;
}

TEST(OccluderSkins, MaxBoxesAndMinVolumeStopTheSearch)
{
    // Three separate closed boxes in one mesh (three interiors): skins of
    // about 7^3, 3^3 and 1^3 m^3 at 0.5 m voxels. The smallest comes first
    // in scan order (lowest z).
    Mesh m = box_mesh(Aabb::of({0, 0, 20}, {8, 8, 28}), "three");
    append_box(m, Aabb::of({12, 0, 10}, {16, 4, 14}));
    append_box(m, Aabb::of({20, 0, 0}, {22, 2, 2}));
    m.update_bounds();
    const Aabb big = Aabb::of({0, 0, 20}, {8, 8, 28}), mid = Aabb::of({12, 0, 10}, {16, 4, 14}),
               small = Aabb::of({20, 0, 0}, {22, 2, 2});

    SkinOptions o;
    o.min_volume = 0.5f;
    std::vector<Aabb> skins = skins_of(m, o);
    ASSERT_EQ(skins.size(), 3u);   // densest first: biggest room first
    EXPECT_TRUE(within(skins[0], big));
    EXPECT_TRUE(within(skins[1], mid));
    EXPECT_TRUE(within(skins[2], small));

    o.max_boxes = 2;
    skins = skins_of(m, o);
    ASSERT_EQ(skins.size(), 2u);
    EXPECT_TRUE(within(skins[1], mid));

    // Threshold 2: the small box (under 8 m^3) is rejected and the search ends.
    o.max_boxes = 8;
    o.min_volume = 10.0f;
    skins = skins_of(m, o);
    ASSERT_EQ(skins.size(), 2u);
    EXPECT_TRUE(within(skins[0], big));
    EXPECT_TRUE(within(skins[1], mid));

    // From the first voxel the small box comes first, and ends the search
    // although the others would pass: watertight, so an empty list.
    o.start = SkinOptions::Start::first;
    std::string why;
    const auto none = occluder_skins(m, o, &why);
    ASSERT_TRUE(none.has_value()) << why;
    EXPECT_TRUE(none->empty());

    o.min_volume = 0.5f;
    o.max_boxes = 1;
    skins = skins_of(m, o);
    ASSERT_EQ(skins.size(), 1u);
    EXPECT_TRUE(within(skins[0], small));
}

TEST(OccluderSkins, DensestStartGivesALargerFirstBoxThanTheFirstVoxel)
{
    // An L: a thin arm (10 x 2 x 2 m) at low z, where scan order starts,
    // under a 10 m cube. Grown from the arm's first voxel, a box stays as
    // thin as the arm; from the densest voxel it fills the cube.
    std::vector<glm::ivec3> cells = cell_block({0, 0, 2}, {10, 10, 12});
    for (const glm::ivec3 &c : cell_block({0, 0, 0}, {10, 2, 2}))
        cells.push_back(c);
    const Mesh l = cells_mesh(cells, 1.0f);
    SkinOptions densest, first;
    first.start = SkinOptions::Start::first;
    densest.max_boxes = first.max_boxes = 1;
    const std::vector<Aabb> a = skins_of(l, densest), b = skins_of(l, first);
    ASSERT_EQ(a.size(), 1u);
    ASSERT_EQ(b.size(), 1u);
    EXPECT_LT(b.front().min.z, 2.0f);   // the first voxel is in the arm
    EXPECT_GE(volume(a.front()), 2.0f * volume(b.front()));
    EXPECT_GT(volume(a.front()), 0.7f * 1000.0f);
    std::mt19937 rng(17);
    EXPECT_EQ(points_outside(l, a.front(), 100, rng), 0);
    EXPECT_EQ(points_outside(l, b.front(), 100, rng), 0);
}

namespace {

std::string temp_file(const std::string &name, const std::string &text)
{
    const std::string path = ::testing::TempDir() + name;
    std::ofstream(path) << text;
    return path;
}

std::string load_error(const std::string &path)
{
    try {
        OccluderSkinDatabase::load(path);
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "";
}

// Meshes of every kind: skins, several boxes, a leaky one (skipped).
Scene sample_scene()
{
    Scene scene;
    scene.meshes.push_back(box_mesh(Aabb::of({0, 0, 0}, {8, 6, 10}), "a"));
    Mesh leaky = box_mesh(Aabb::of({20, 0, 0}, {28, 6, 10}), "leaky # really");
    leaky.indices.resize(leaky.indices.size() - 3);
    scene.meshes.push_back(leaky);
    Mesh u = u_mesh();
    for (glm::vec3 &p : u.positions)
        p += glm::vec3(0.0f, 0.0f, 30.0f);
    scene.meshes.push_back(u);
    scene.meshes.push_back(box_mesh(Aabb::of({40, 0, 0}, {43.3f, 5.1f, 7.7f}), "d"));
    scene.meshes.push_back(box_mesh(Aabb::of({50, 0, 0}, {60, 0.5f, 10}), "thin"));
    scene.update_bounds();
    return scene;
}

const char *const sample_header = "occu-database occluder-skins 1\n"
                                  "algorithm occluder-skins\n"
                                  "settings voxel=0.5 max-boxes=8 min-volume=1 start=densest\n"
                                  "scene 00000000deadbeef meshes=10 triangles=1200\n"
                                  "code 0123456789ab\n"
                                  "mesa none\n";

}  // namespace

TEST(OccluderSkinsDatabase, RoundTripsThroughItsFile)
{
    const Scene scene = sample_scene();
    const OccluderSkinDatabase db = OccluderSkinDatabase::make(scene, SkinOptions{});
    EXPECT_EQ(db.mesh_count(), scene.meshes.size());
    EXPECT_EQ(db.skipped.size(), 2u);   // leaky, thin
    EXPECT_GT(db.boxes(2).size(), 1u);
    EXPECT_TRUE(db.boxes(1).empty());
    EXPECT_EQ(db.provenance.algorithm, "occluder-skins");
    EXPECT_EQ(db.provenance.code, std::string(library_code_hash()));
    EXPECT_EQ(db.provenance.mesa, "none") << "skins are pure geometry";
    EXPECT_EQ(db.provenance.settings, SkinOptions{}.describe());
    EXPECT_EQ(db.provenance.scene, scene_geometry_fingerprint(scene) + " meshes=" +
                                       std::to_string(scene.meshes.size()) + " triangles=" +
                                       std::to_string(scene.triangle_count()));
    EXPECT_EQ(db.meshes, scene.meshes.size());
    EXPECT_TRUE(db.provenance.mismatch(skin_scene_provenance(scene)).empty());

    const std::string path = ::testing::TempDir() + "skins_roundtrip.txt";
    db.save(path);
    const OccluderSkinDatabase back = OccluderSkinDatabase::load(path);
    EXPECT_TRUE(back == db);
    EXPECT_NE(back.skipped.at(1).find("not watertight"), std::string::npos) << back.skipped.at(1);

    // Another scene is named as such.
    Scene other = scene;
    other.meshes[0].positions[0].x += 0.5f;
    EXPECT_NE(back.provenance.mismatch(skin_scene_provenance(other)).find("made for another scene"), std::string::npos);
}

TEST(OccluderSkinsDatabase, BadLinesAreRefusedNamingFileAndLine)
{
    const std::string header = sample_header;
    struct Case {
        std::string body, expect;
    } cases[] = {
        {"skins 3 1 0 0 0 1 1\nend\n", ":7: skins: box 0 of mesh 3: Z1 missing"},
        {"skins 3 1 0 0 0 1 1 1 9\nend\n", ":7: skins: more fields than it takes ('9')"},
        {"skins 3 1 0 0 0 1 x 1\nend\n", ":7: skins: box 0 of mesh 3: Y1 is 'x', not a number"},
        {"skins 3 1 0 2 0 1 1 1\nend\n", ":7: box 0 of mesh 3 is empty"},
        {"skins 10 0\nend\n", ":7: skins: the mesh is 10, more than 9"},
        {"skins -1 0\nend\n", ":7: skins: the mesh is '-1', not a whole number"},
        {"skins 3 0\nskipped 3 why\nend\n", ":8: mesh 3 repeats"},
        {"skipped 4\nend\n", ":7: skipped wants MESH REASON"},
        {"boxes 3 0\nend\n", ":7: unknown record 'boxes'"},
        {"scene 00000000deadbeef meshes=10 triangles=1200\nend\n", ":7: unknown record 'scene'"},
        {"skins 3 0\n", ":8: ends before its end record"},
    };
    int k = 0;
    for (const Case &c : cases) {
        const std::string name = "skins_bad_" + std::to_string(k++) + ".txt";
        const std::string error = load_error(temp_file(name, header + c.body));
        EXPECT_NE(error.find(name + c.expect), std::string::npos) << error;
    }
    EXPECT_NE(load_error(temp_file("skins_notdb.txt", "occu-database occluder-sets 1\n"))
                  .find("skins_notdb.txt:1: a database of occluder-sets, not an occu occluder skin database"),
              std::string::npos);
    EXPECT_NE(load_error(temp_file("skins_v2.txt", "occu-database occluder-skins 2\n"))
                  .find("skins_v2.txt:1: occluder skin database version 2"),
              std::string::npos);
    EXPECT_NE(load_error(temp_file("skins_old.txt", "occu-occluder-skins 1\n"))
                  .find("skins_old.txt:1: 'occu-occluder-skins' is the format before occu-database"),
              std::string::npos);
    EXPECT_NE(load_error(temp_file("skins_algorithm.txt", "occu-database occluder-skins 1\nalgorithm boxes\nsettings\n"
                                                          "scene f meshes=1\ncode c\nmesa none\nend\n"))
                  .find("skins_algorithm.txt:2: algorithm 'boxes'"),
              std::string::npos);
    EXPECT_NE(load_error(temp_file("skins_nomeshes.txt", "occu-database occluder-skins 1\nalgorithm occluder-skins\n"
                                                         "settings\nscene f\ncode c\nmesa none\nend\n"))
                  .find("skins_nomeshes.txt:4: scene: meshes=VALUE missing"),
              std::string::npos);
    EXPECT_NE(load_error(::testing::TempDir() + "skins_missing.txt").find("skins_missing.txt: cannot open"), std::string::npos);
    // A good one loads.
    const std::string good = temp_file("skins_good.txt", header + "skins 3 2 0 0 0 1 1 1  -2 -2 -2 -1 0.5 -1  # two\n"
                                                                  "skipped 4 not watertight: a hole\nend\n");
    const OccluderSkinDatabase db = OccluderSkinDatabase::load(good);
    ASSERT_EQ(db.boxes(3).size(), 2u);
    EXPECT_EQ(db.boxes(3)[1].max.y, 0.5f);
    EXPECT_EQ(db.skipped.at(4), "not watertight: a hole");
}

TEST(OccluderSkinsDatabase, NonFiniteCoordinatesAreRefused)
{
    for (const char *bad : {"nan", "inf", "-inf", "1e39"}) {
        const std::string name = std::string("skins_nonfinite_") + (bad[0] == '-' ? "minf" : bad) + ".txt";
        const std::string error =
            load_error(temp_file(name, std::string(sample_header) + "skins 2 1 0 0 0 1 " + bad + " 1\nend\n"));
        EXPECT_NE(error.find(name + ":7: skins: box 0 of mesh 2: Y1 is '" + bad + "', not a finite number"),
                  std::string::npos)
            << error;
    }
}

TEST(OccluderSkinsDatabase, ShardsMergeToTheUnshardedResult)
{
    const Scene scene = sample_scene();
    const OccluderSkinDatabase whole = OccluderSkinDatabase::make(scene, SkinOptions{});
    const OccluderSkinDatabase one = OccluderSkinDatabase::make(scene, SkinOptions{}, 1, 2);
    const OccluderSkinDatabase two = OccluderSkinDatabase::make(scene, SkinOptions{}, 2, 2);
    EXPECT_EQ(one.mesh_count(), 3u);   // meshes 0, 2, 4
    EXPECT_EQ(two.mesh_count(), 2u);   // meshes 1, 3
    // Through their files, as occu-preprocess merges them.
    const std::string p1 = ::testing::TempDir() + "skins_shard1.txt", p2 = ::testing::TempDir() + "skins_shard2.txt";
    one.save(p1);
    two.save(p2);
    const OccluderSkinDatabase merged =
        OccluderSkinDatabase::merge({OccluderSkinDatabase::load(p2), OccluderSkinDatabase::load(p1)});
    EXPECT_TRUE(merged == whole);

    // Shards of different options, or overlapping, are refused naming why.
    SkinOptions coarse;
    coarse.voxel_size = 1.0f;
    const OccluderSkinDatabase other = OccluderSkinDatabase::make(scene, coarse, 2, 2);
    try {
        OccluderSkinDatabase::merge({one, other}, {"one.txt", "other.txt"});
        ADD_FAILURE() << "merged shards of different options";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("other.txt was made otherwise than one.txt: settings 'voxel=1 "),
                  std::string::npos)
            << e.what();
    }
    try {
        OccluderSkinDatabase::merge({one, whole});
        ADD_FAILURE() << "merged overlapping shards";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("mesh 0 is in shard 2 and in an earlier shard"), std::string::npos)
            << e.what();
    }
}
