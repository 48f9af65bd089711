// SPDX-License-Identifier: MIT
// The Quake III level reader (scene/quake3_bsp.h) on minimal levels built
// here, lump by lump, and on one of Debian's OpenArena levels.
#include "scene/quake3_bsp.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "occluders/brush_occluders.h"
#include "scene/scene_file.h"

using namespace occu;

namespace {

std::string temp(const char *name)
{
    return ::testing::TempDir() + "occu_" + std::to_string(getpid()) + "_" + name;
}

// A level as its lumps' records, laid out by bytes().
struct BspFile {
    struct Texture {
        std::string name;
        std::uint32_t surface_flags, content_flags;
    };
    struct Node {
        std::int32_t plane, front, back;
        std::int32_t mins[3], maxs[3];
    };
    struct Leaf {
        std::int32_t cluster, area;
        std::int32_t mins[3], maxs[3];
        std::int32_t leaf_face, leaf_face_count, leaf_brush, leaf_brush_count;
    };
    struct Model {
        std::int32_t face, face_count, brush = 0, brush_count = 0;
    };
    struct Brush {
        std::int32_t side, side_count, texture;
    };
    struct BrushSide {
        std::int32_t plane, texture;
    };
    struct Vertex {
        glm::vec3 position, normal;
    };
    struct Face {
        std::int32_t texture, type, vertex, vertex_count, meshvert, meshvert_count;
        glm::vec3 normal;
        std::int32_t width = 0, height = 0;
    };

    std::string entities;
    std::vector<Texture> textures;
    std::vector<glm::vec4> planes;
    std::vector<Node> nodes;
    std::vector<Leaf> leaves;
    std::vector<std::int32_t> leaf_faces;
    std::vector<Model> models;
    std::vector<Brush> brushes;
    std::vector<BrushSide> brush_sides;
    std::vector<Vertex> vertices;
    std::vector<std::int32_t> meshverts;
    std::vector<Face> faces;
    std::vector<std::uint8_t> visdata;   // with its two counts
    std::int32_t version = 46;

    std::vector<char> bytes() const
    {
        std::vector<std::vector<char>> lumps(17);
        auto i32 = [](std::vector<char> &out, std::int32_t v) {
            for (int b = 0; b < 4; ++b)
                out.push_back(char((std::uint32_t(v) >> (8 * b)) & 0xff));
        };
        auto f32 = [&](std::vector<char> &out, float f) {
            std::int32_t v;
            std::memcpy(&v, &f, 4);
            i32(out, v);
        };
        auto v3 = [&](std::vector<char> &out, const glm::vec3 &v) {
            f32(out, v.x);
            f32(out, v.y);
            f32(out, v.z);
        };
        lumps[0].assign(entities.begin(), entities.end());
        lumps[0].push_back('\0');
        for (const Texture &t : textures) {
            std::vector<char> name(64, '\0');
            std::copy(t.name.begin(), t.name.end(), name.begin());
            lumps[1].insert(lumps[1].end(), name.begin(), name.end());
            i32(lumps[1], std::int32_t(t.surface_flags));
            i32(lumps[1], std::int32_t(t.content_flags));
        }
        for (const glm::vec4 &p : planes) {
            v3(lumps[2], glm::vec3(p));
            f32(lumps[2], p.w);
        }
        for (const Node &n : nodes) {
            for (std::int32_t v : {n.plane, n.front, n.back, n.mins[0], n.mins[1], n.mins[2], n.maxs[0], n.maxs[1], n.maxs[2]})
                i32(lumps[3], v);
        }
        for (const Leaf &l : leaves)
            for (std::int32_t v : {l.cluster, l.area, l.mins[0], l.mins[1], l.mins[2], l.maxs[0], l.maxs[1], l.maxs[2],
                                   l.leaf_face, l.leaf_face_count, l.leaf_brush, l.leaf_brush_count})
                i32(lumps[4], v);
        for (std::int32_t f : leaf_faces)
            i32(lumps[5], f);
        for (const Model &m : models) {
            for (int k = 0; k < 6; ++k)
                f32(lumps[7], 0.0f);
            for (std::int32_t v : {m.face, m.face_count, m.brush, m.brush_count})
                i32(lumps[7], v);
        }
        for (const Brush &b : brushes)
            for (std::int32_t v : {b.side, b.side_count, b.texture})
                i32(lumps[8], v);
        for (const BrushSide &b : brush_sides)
            for (std::int32_t v : {b.plane, b.texture})
                i32(lumps[9], v);
        for (const Vertex &v : vertices) {
            v3(lumps[10], v.position);
            for (int k = 0; k < 4; ++k)
                f32(lumps[10], 0.0f);   // texture and lightmap coordinates
            v3(lumps[10], v.normal);
            i32(lumps[10], -1);          // colour
        }
        for (std::int32_t m : meshverts)
            i32(lumps[11], m);
        for (const Face &f : faces) {
            for (std::int32_t v : {f.texture, -1, f.type, f.vertex, f.vertex_count, f.meshvert, f.meshvert_count, -1, 0, 0, 0, 0})
                i32(lumps[13], v);
            for (int k = 0; k < 9; ++k)
                f32(lumps[13], 0.0f);   // lightmap origin and vectors
            v3(lumps[13], f.normal);
            i32(lumps[13], f.width);
            i32(lumps[13], f.height);
        }
        lumps[16].assign(visdata.begin(), visdata.end());

        std::vector<char> out = {'I', 'B', 'S', 'P'};
        i32(out, version);
        std::size_t at = 8 + 17 * 8;
        for (const auto &l : lumps) {
            i32(out, std::int32_t(at));
            i32(out, std::int32_t(l.size()));
            at += l.size();
        }
        for (const auto &l : lumps)
            out.insert(out.end(), l.begin(), l.end());
        return out;
    }
};

constexpr std::uint32_t surf_sky = 0x4, surf_nodraw = 0x80, contents_solid = 0x1, contents_translucent = 0x20000000;

// The control points of the test patch: a hump over [0, 64]^2 (Quake
// units), rows along y, columns along x.
const float patch_heights[3][3] = {{0, 16, 0}, {16, 64, 16}, {0, 16, 0}};

// One face of each kind over a cube of 64 units, two leaves split by the
// plane x = 32, two clusters of which the second sees the first but not the
// other way round, and two spawn points.
BspFile minimal_level()
{
    BspFile f;
    f.textures = {{"textures/test/wall", 0, contents_solid},
                  {"textures/common/nodraw", surf_nodraw, contents_solid},
                  {"textures/skies/sky", surf_sky, contents_solid},
                  {"textures/test/glass", 0, contents_translucent | contents_solid},
                  {"flareShader", 0, contents_solid}};
    const glm::vec3 up(0, 0, 1), down(0, 0, -1);
    // 0-3: a floor quad; 4-6: a ceiling triangle; 7-15: the patch; 16: a flare.
    f.vertices = {{{0, 0, 0}, up}, {{64, 0, 0}, up}, {{64, 64, 0}, up}, {{0, 64, 0}, up},
                  {{0, 0, 64}, down}, {{64, 0, 64}, down}, {{0, 64, 64}, down}};
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            f.vertices.push_back({{32.0f * col, 32.0f * row, patch_heights[row][col]}, up});
    f.vertices.push_back({{32, 32, 32}, up});
    // The compiler's winding: clockwise seen from the front.
    f.meshverts = {0, 2, 1, 0, 3, 2, 0, 1, 2};
    f.faces = {{0, 1, 0, 4, 0, 6, up},        // polygon
               {0, 3, 4, 3, 6, 3, down},      // mesh
               {0, 2, 7, 9, 0, 0, up, 3, 3},  // patch
               {4, 4, 16, 1, 0, 0, up},       // billboard
               {1, 1, 0, 4, 0, 6, up},        // nodraw
               {2, 1, 0, 4, 0, 6, up},        // sky
               {3, 1, 0, 4, 0, 6, up}};       // glass
    f.planes = {{1, 0, 0, 32}};
    f.nodes = {{0, -1, -2, {0, 0, 0}, {64, 64, 64}}};
    f.leaves = {{0, 0, {32, 0, 0}, {64, 64, 64}, 0, 3, 0, 0}, {1, 0, {0, 0, 0}, {32, 64, 64}, 3, 2, 0, 0}};
    f.leaf_faces = {0, 1, 2, 0, 6};
    f.models = {{0, 7}};
    f.visdata = {2, 0, 0, 0, 1, 0, 0, 0, 0x1, 0x3};
    f.entities = "{\n\"classname\" \"worldspawn\"\n}\n"
                 "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"16 16 24\"\n\"angle\" \"90\"\n}\n"
                 "{\n\"classname\" \"team_CTF_bluespawn\"\n\"origin\" \"48 48 24\"\n\"angles\" \"0 180 0\"\n}\n"
                 "{\n\"classname\" \"light\"\n\"origin\" \"1 2 3\"\n}\n";
    return f;
}

Scene read(const BspFile &f, const Quake3Options &options = {})
{
    std::vector<std::string> warnings;
    return read_quake3_bsp("test.bsp", f.bytes(), options, warnings);
}

// What the reader says refusing `bytes`, or "" when it reads them.
std::string refusal_of_bytes(const std::vector<char> &bytes)
{
    std::vector<std::string> warnings;
    try {
        read_quake3_bsp("test.bsp", bytes, {}, warnings);
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "";
}

std::string refusal_of(const std::function<void(BspFile &)> &change)
{
    BspFile f = minimal_level();
    change(f);
    return refusal_of_bytes(f.bytes());
}

const Mesh *mesh_named(const Scene &s, const std::string &name)
{
    for (const Mesh &m : s.meshes)
        if (m.name == name)
            return &m;
    return nullptr;
}

glm::vec3 q(float x, float y, float z) { return quake3_to_occu(glm::vec3(x, y, z)); }

void expect_near(const glm::vec3 &a, const glm::vec3 &b, float tolerance = 1e-5f)
{
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

// Triangles of `mesh` whose corners are collinear to float precision: the
// third within float rounding of its coordinates (a float step at their
// largest magnitude) of the line through the other two.
std::size_t collinear_triangles(const Mesh &mesh, std::uint32_t first_index = 0, std::uint32_t index_count = ~0u)
{
    std::size_t n = 0;
    const std::size_t end = std::min<std::size_t>(mesh.indices.size(), std::size_t(first_index) + index_count);
    for (std::size_t t = first_index; t + 2 < end; t += 3) {
        const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
            c(mesh.positions[mesh.indices[t + 2]]);
        const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
        const double magnitude = std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z), std::abs(b.x), std::abs(b.y),
                                           std::abs(b.z), std::abs(c.x), std::abs(c.y), std::abs(c.z)});
        n += glm::length(glm::cross(b - a, c - a)) <= longest * magnitude * std::numeric_limits<float>::epsilon();
    }
    return n;
}

}  // namespace

TEST(Quake3Bsp, CoordinatesAreYUpMetres)
{
    expect_near(q(100, 200, 300), {2.54f, 7.62f, -5.08f});
}

TEST(Quake3Bsp, EveryFaceTypeAndTextureRule)
{
    for (int segments : {1, 8}) {
        const Scene s = read(minimal_level(), Quake3Options{segments});
        const Mesh *wall = mesh_named(s, "textures/test/wall"), *glass = mesh_named(s, "textures/test/glass"),
                   *sky = mesh_named(s, "textures/skies/sky");
        ASSERT_TRUE(wall && glass && sky);
        EXPECT_EQ(s.meshes.size(), 3u) << "nodraw and billboard faces make no mesh";
        // The sky is drawn where its faces are, an opaque unlit wall: what
        // a player sees there (scene/quake3_bsp.h).
        EXPECT_EQ(sky->triangle_count(), 2u);
        EXPECT_TRUE(sky->occluder);
        EXPECT_FALSE(sky->shaded);
        EXPECT_TRUE(wall->shaded);
        // Polygon 2 + mesh 1 + patch 2 a quad.
        EXPECT_EQ(wall->triangle_count(), std::size_t(3 + 2 * segments * segments));
        EXPECT_TRUE(wall->occluder);
        EXPECT_EQ(glass->triangle_count(), 2u);
        EXPECT_FALSE(glass->occluder) << "CONTENTS_TRANSLUCENT: drawn, never an occluder";
        const Level &level = *s.level;
        ASSERT_EQ(level.faces.size(), 7u);
        EXPECT_EQ(level.patch_count, 1u);
        EXPECT_EQ(level.billboard_count, 1u);
        EXPECT_EQ(level.hidden_face_count, 1u);
        EXPECT_EQ(level.see_through_face_count, 1u);
        EXPECT_EQ(level.faces[5].mesh, std::int32_t(sky - s.meshes.data()));
        for (int f : {3, 4})
            EXPECT_EQ(level.faces[std::size_t(f)].mesh, -1) << "face " << f;
        EXPECT_EQ(level.faces[2].index_count, std::uint32_t(6 * segments * segments));
        for (const Mesh &m : s.meshes) {
            EXPECT_EQ(m.normals.size(), m.positions.size());
            for (const glm::vec3 &n : m.normals)
                EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
        }
        expect_near(s.bounds.min, glm::min(q(0, 0, 0), q(64, 64, 64)));
        expect_near(s.bounds.max, glm::max(q(0, 0, 0), q(64, 64, 64)));
    }
}

TEST(Quake3Bsp, TrianglesAreCounterClockwiseSeenFromTheirFront)
{
    const Scene s = read(minimal_level());
    const Mesh &wall = *mesh_named(s, "textures/test/wall");
    const Level &level = *s.level;
    // The floor and the patch face up (occu's +y), the ceiling down.
    for (int f : {0, 1, 2}) {
        const Level::Face &face = level.faces[std::size_t(f)];
        const glm::vec3 front = f == 1 ? glm::vec3(0, -1, 0) : glm::vec3(0, 1, 0);
        ASSERT_GT(face.index_count, 0u);
        for (std::uint32_t t = face.first_index; t < face.first_index + face.index_count; t += 3) {
            const glm::vec3 &a = wall.positions[wall.indices[t]], &b = wall.positions[wall.indices[t + 1]],
                            &c = wall.positions[wall.indices[t + 2]];
            EXPECT_GT(glm::dot(glm::cross(b - a, c - a), front), 0.0f) << "face " << f << " triangle " << t / 3;
        }
    }
}

// A polygon face with a vertex on one of its edges (a compiler's fix of a
// T-junction), fanned from an end of that edge: one triangle of the fan has
// collinear corners, no surface. GL draws nothing of it that a player
// should see, but llvmpipe can rasterize such a triangle's edge through a
// pixel centre with its depth and colour interpolated over an area that is
// rounding noise: oa_thor's floor (textures/cosmo_floor/bfloor3) drew one
// black pixel at depth 0, in front of everything, from spawn:2's frame 320
// at 1280 x 720, which no box test can keep. The reader leaves such
// triangles out, the face's range holding the others; oa_thor keeps none.
TEST(Quake3Bsp, TrianglesWithCollinearCornersAreLeftOut)
{
    BspFile f = minimal_level();
    const glm::vec3 up(0, 0, 1);
    const std::int32_t first = std::int32_t(f.vertices.size()), meshvert = std::int32_t(f.meshverts.size());
    // A, T on A-B, B, C, D; the fan from A, clockwise from the front.
    f.vertices.insert(f.vertices.end(), {{{0, 0, 8}, up}, {{21, 7, 8}, up}, {{60, 20, 8}, up}, {{64, 64, 8}, up},
                                         {{0, 64, 8}, up}});
    f.meshverts.insert(f.meshverts.end(), {0, 2, 1, 0, 3, 2, 0, 4, 3});
    f.faces.push_back({0, 1, first, 5, meshvert, 9, up});
    f.models[0].face_count = std::int32_t(f.faces.size());
    const Scene s = read(f);
    const Level::Face &face = s.level->faces.back();
    ASSERT_GE(face.mesh, 0);
    const Mesh &wall = s.meshes[std::size_t(face.mesh)];
    EXPECT_EQ(face.index_count, 6u) << "A-B-C and A-C-D, not A-T-B";
    EXPECT_EQ(collinear_triangles(wall, face.first_index, face.index_count), 0u);
    EXPECT_LE(face.first_index + face.index_count, wall.indices.size());

    const std::string pk3 = "/usr/share/games/openarena/baseoa/pak6-patch088.pk3";
    ASSERT_TRUE(std::ifstream(pk3).good()) << pk3 << " is missing: tools/deps.sh test installs openarena-088-data";
    const Scene thor = load_scene(pk3 + ":maps/oa_thor.bsp");
    std::size_t collinear = 0;
    for (const Mesh &m : thor.meshes)
        collinear += collinear_triangles(m);
    EXPECT_EQ(collinear, 0u) << "of oa_thor's " << thor.triangle_count() << " triangles";
    for (const Level::Face &level_face : thor.level->faces)
        if (level_face.mesh >= 0) {
            EXPECT_LE(level_face.first_index + level_face.index_count,
                      thor.meshes[std::size_t(level_face.mesh)].indices.size());
        }
}

TEST(Quake3Bsp, PatchVerticesLieOnTheBiquadraticBezierSurface)
{
    const int segments = 4;
    const Scene s = read(minimal_level(), Quake3Options{segments});
    const Mesh &wall = *mesh_named(s, "textures/test/wall");
    const Level::Face &patch = s.level->faces[2];
    auto bezier = [](float u, float v) {
        const float bu[3] = {(1 - u) * (1 - u), 2 * u * (1 - u), u * u};
        const float bv[3] = {(1 - v) * (1 - v), 2 * v * (1 - v), v * v};
        glm::vec3 p(0.0f);
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 3; ++col)
                p += bu[col] * bv[row] * glm::vec3(32.0f * col, 32.0f * row, patch_heights[row][col]);
        return quake3_to_occu(p);
    };
    // Every grid point (u, v) = (i, j) / segments is among the patch's vertices.
    std::vector<bool> found((segments + 1) * (segments + 1), false);
    for (std::uint32_t t = patch.first_index; t < patch.first_index + patch.index_count; ++t) {
        const glm::vec3 &p = wall.positions[wall.indices[t]];
        bool on_grid = false;
        for (int j = 0; j <= segments; ++j)
            for (int i = 0; i <= segments; ++i)
                if (glm::length(p - bezier(float(i) / segments, float(j) / segments)) < 1e-5f) {
                    found[std::size_t(j * (segments + 1) + i)] = true;
                    on_grid = true;
                }
        EXPECT_TRUE(on_grid) << "vertex (" << p.x << ", " << p.y << ", " << p.z << ") is no grid point of the surface";
    }
    for (std::size_t k = 0; k < found.size(); ++k)
        EXPECT_TRUE(found[k]) << "grid point " << k << " missing";
    // The formula itself at the middle: weights 1/4, 1/2, 1/4 each way, so
    // the centre point counts 1/4 and each edge midpoint 1/8: 64/4 + 4 * 16/8.
    expect_near(bezier(0.5f, 0.5f), q(32, 32, 24));
}

TEST(Quake3Bsp, PatchOfTwoPiecesSharesItsMiddleColumn)
{
    BspFile f = minimal_level();
    // A 5 x 3 patch: two pieces side by side, the second a flat ramp.
    std::vector<BspFile::Vertex> control;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 5; ++col)
            control.push_back({{16.0f * col, 32.0f * row, col <= 2 ? patch_heights[row][col] : 0.0f}, {0, 0, 1}});
    const auto first = std::int32_t(f.vertices.size());
    f.vertices.insert(f.vertices.end(), control.begin(), control.end());
    f.faces[2] = {0, 2, first, 15, 0, 0, {0, 0, 1}, 5, 3};
    const Scene s = read(f, Quake3Options{2});
    const Level::Face &patch = s.level->faces[2];
    EXPECT_EQ(patch.index_count, 2u * 2u * 2u * 2u * 3u) << "two pieces of 2 x 2 quads";
    // (4 + 1) x (2 + 1) grid vertices, none twice.
    const Mesh &wall = *mesh_named(s, "textures/test/wall");
    std::vector<std::uint32_t> used(wall.indices.begin() + patch.first_index,
                                    wall.indices.begin() + patch.first_index + patch.index_count);
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    EXPECT_EQ(used.size(), 15u);
}

TEST(Quake3Bsp, PatchStraightOneWayIsOneSegmentThatWay)
{
    // A vault: curved along x (columns), straight along y (rows, each middle
    // row halfway between its neighbours).
    BspFile f = minimal_level();
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            f.vertices[std::size_t(7 + row * 3 + col)].position = {32.0f * col, 32.0f * row, col == 1 ? 64.0f : 0.0f};
    const Scene s = read(f, Quake3Options{8});
    EXPECT_EQ(s.level->faces[2].index_count, 8u * 1u * 6u) << "8 segments across the curve, 1 along the straight way";
    const Mesh &wall = *mesh_named(s, "textures/test/wall");
    const Level::Face &patch = s.level->faces[2];
    for (std::uint32_t t = patch.first_index; t < patch.first_index + patch.index_count; ++t) {
        // On the parabola z = 64 * 2u(1 - u), u = x / 64, whatever y.
        const glm::vec3 p = wall.positions[wall.indices[t]] / quake3_unit_metres;
        const float u = p.x / 64.0f;
        EXPECT_NEAR(p.y, 64.0f * 2.0f * u * (1.0f - u), 1e-3f);
    }
}

TEST(Quake3Bsp, TreeLeavesClustersAndVisibility)
{
    const Scene s = read(minimal_level());
    const Level &level = *s.level;
    ASSERT_EQ(level.nodes.size(), 1u);
    ASSERT_EQ(level.leaves.size(), 2u);
    EXPECT_EQ(level.leaf_at(q(48, 10, 10)), 0) << "in front of x = 32";
    EXPECT_EQ(level.leaf_at(q(10, 10, 10)), 1);
    EXPECT_EQ(level.leaves[1].cluster, 1);
    EXPECT_EQ(level.leaves[1].leaf_face_count, 2u);
    EXPECT_EQ(level.leaf_faces[level.leaves[1].first_leaf_face + 1], 6u);
    expect_near(level.leaves[0].bounds.min, glm::min(q(32, 0, 0), q(64, 64, 64)));
    EXPECT_EQ(level.cluster_count, 2);
    EXPECT_TRUE(level.cluster_sees(0, 0));
    EXPECT_FALSE(level.cluster_sees(0, 1));
    EXPECT_TRUE(level.cluster_sees(1, 0));
    EXPECT_TRUE(level.cluster_sees(1, 1));
    EXPECT_TRUE(level.cluster_sees(-1, 1)) << "from a solid leaf: nothing known, everything may be seen";
    expect_near(level.planes[0].normal, {1, 0, 0});
    EXPECT_NEAR(level.planes[0].distance, 32 * quake3_unit_metres, 1e-6f);
}

TEST(Quake3Bsp, LevelWithoutVisibilitySeesEverything)
{
    BspFile f = minimal_level();
    f.visdata.clear();
    const Scene s = read(f);
    EXPECT_EQ(s.level->cluster_count, 0);
    EXPECT_TRUE(s.level->cluster_sees(0, 1));
}

TEST(Quake3Bsp, SpawnPointsAtEyeHeightLookingAlongTheirAngle)
{
    const Scene s = read(minimal_level());
    const std::vector<LevelSpawn> &spawns = s.level->spawns;
    ASSERT_EQ(spawns.size(), 2u) << "worldspawn and light are no spawn points";
    EXPECT_EQ(spawns[0].classname, "info_player_deathmatch");
    expect_near(spawns[0].origin, q(16, 16, 24));
    expect_near(spawns[0].eye, q(16, 16, 24 + 9 + 26));
    EXPECT_FLOAT_EQ(spawns[0].yaw_degrees, 90.0f);
    expect_near(spawns[0].direction, {0, 0, -1});   // yaw 90: Quake's +y, occu's -z
    EXPECT_EQ(spawns[1].classname, "team_CTF_bluespawn");
    EXPECT_FLOAT_EQ(spawns[1].yaw_degrees, 180.0f) << "the yaw of 'angles'";
    expect_near(spawns[1].direction, {-1, 0, 0});
}

// Adds to `f` a world brush over [lo, hi] (Quake units) with the texture
// `texture` on every side but the top, which has `top`.
void add_box_brush(BspFile &f, glm::ivec3 lo, glm::ivec3 hi, std::int32_t texture, std::int32_t top)
{
    const std::int32_t first = std::int32_t(f.brush_sides.size());
    for (int a = 0; a < 3; ++a)
        for (int high = 0; high < 2; ++high) {
            glm::vec3 n(0.0f);
            n[a] = high ? 1.0f : -1.0f;
            f.planes.push_back(glm::vec4(n, high ? float(hi[a]) : -float(lo[a])));
            f.brush_sides.push_back({std::int32_t(f.planes.size() - 1), a == 2 && high ? top : texture});
        }
    f.brushes.push_back({first, 6, texture});
    f.models[0].brush_count = std::int32_t(f.brushes.size());
}

// Adds a square polygon face at height z over [x0, x1] x [y0, y1], facing
// up (or down).
void add_square_face(BspFile &f, float z, float x0, float x1, float y0, float y1, bool facing_up)
{
    const glm::vec3 n(0, 0, facing_up ? 1.0f : -1.0f);
    const std::int32_t first = std::int32_t(f.vertices.size()), meshvert = std::int32_t(f.meshverts.size());
    f.vertices.insert(f.vertices.end(), {{{x0, y0, z}, n}, {{x1, y0, z}, n}, {{x1, y1, z}, n}, {{x0, y1, z}, n}});
    if (facing_up)
        f.meshverts.insert(f.meshverts.end(), {0, 2, 1, 0, 3, 2});
    else
        f.meshverts.insert(f.meshverts.end(), {0, 1, 2, 0, 2, 3});
    f.faces.push_back({0, 1, first, 4, meshvert, 6, n});
    f.models[0].face_count = std::int32_t(f.faces.size());
}

TEST(Quake3Bsp, BoxBrushSidesCountAsDrawnOnlyWhereTheLevelsOwnFacesCoverThem)
{
    BspFile f = minimal_level();
    // 0: a caulked box whose top is drawn and has its face: one drawn side.
    add_box_brush(f, {100, 0, 0}, {132, 32, 32}, 1, 0);
    add_square_face(f, 32, 100, 132, 0, 32, true);
    // 1: its top's shader is drawn, but the compiler kept only half the
    // face (the rest against the void or another brush): no drawn side.
    add_box_brush(f, {200, 0, 0}, {232, 32, 32}, 1, 0);
    add_square_face(f, 32, 200, 216, 0, 32, true);
    // 2: a whole face in the top's plane, but facing into the brush.
    add_box_brush(f, {300, 0, 0}, {332, 32, 32}, 1, 0);
    add_square_face(f, 32, 300, 332, 0, 32, false);
    // 3: covered by two faces that meet: drawn.
    add_box_brush(f, {400, 0, 0}, {432, 32, 32}, 1, 0);
    add_square_face(f, 32, 400, 416, 0, 32, true);
    add_square_face(f, 32, 416, 432, 0, 32, true);
    // 4: see-through (glass) and 5: a sky side: never occluders.
    add_box_brush(f, {500, 0, 0}, {532, 32, 32}, 3, 3);
    add_square_face(f, 32, 500, 532, 0, 32, true);
    add_box_brush(f, {600, 0, 0}, {632, 32, 32}, 2, 0);
    add_square_face(f, 32, 600, 632, 0, 32, true);

    // 6: a caulked box under box 0, its top against box 0's bottom: closed
    // by box 0 (which must then be closed from the eye), its other sides not.
    add_box_brush(f, {100, 0, -32}, {132, 32, 0}, 1, 1);

    const Scene s = read(f);
    const LevelBrushOccluders level = level_brush_occluders(s);
    const auto &boxes = level.box_brushes;
    ASSERT_EQ(boxes.size(), 3u);
    // Quake's up is occu's +y: side 2 * 1 + 1, down side 2 * 1.
    constexpr std::size_t top = 3, bottom = 2;
    EXPECT_EQ(boxes[0].number, 0);
    EXPECT_EQ(boxes[1].number, 3);
    EXPECT_EQ(boxes[2].number, 6);
    for (const auto &box : boxes)
        for (std::size_t k = 0; k < 6; ++k)
            EXPECT_EQ(box.sides[k].closed, k == top || (box.number == 0 && k == bottom))
                << "brush " << box.number << " side " << k;
    // Boxes 0 and 6 close each other's sides that meet; opaque_brushes
    // holds the opaque solid brushes in the file's order (box 6 the fifth).
    EXPECT_TRUE(boxes[0].sides[top].against.empty());
    EXPECT_EQ(boxes[0].sides[bottom].against, std::vector<std::int32_t>{4});
    EXPECT_EQ(boxes[2].sides[top].against, std::vector<std::int32_t>{0});
    EXPECT_EQ(boxes[2].brush, 4);
    // One unit inside the brush.
    expect_near(boxes[0].bounds.min, glm::min(q(101, 1, 1), q(131, 31, 31)), 1e-4f);
    expect_near(boxes[0].bounds.max, glm::max(q(101, 1, 1), q(131, 31, 31)), 1e-4f);
    // Box 0 hides from an eye above it, not from one beside it (its caulked
    // side faces that eye); box 6 from neither: box 0, against its top,
    // shows that eye its caulked side.
    EXPECT_TRUE(boxes[0].hides_from(q(116, 16, 100), level.opaque_brushes));
    EXPECT_FALSE(boxes[0].hides_from(q(116, 16, 100) + q(100, 0, 0), level.opaque_brushes));
    EXPECT_FALSE(boxes[0].hides_from(q(50, 16, 16), level.opaque_brushes));
    EXPECT_TRUE(boxes[2].hides_from(q(116, 16, 100), level.opaque_brushes));
    EXPECT_FALSE(boxes[2].hides_from(q(116, 16, 100) + q(100, 0, 0), level.opaque_brushes));
    // Every opaque solid brush (not the glass, not the sky one) bounds the eye.
    EXPECT_EQ(s.level->solid_brush_bounds.size(), 5u);
    EXPECT_EQ(s.level->opaque_solids.size(), 5u);
    EXPECT_EQ(level.opaque_brushes.size(), 5u);
}

TEST(Quake3Bsp, BadHeadersAreRefused)
{
    const std::vector<char> good = minimal_level().bytes();
    std::vector<char> magic = good;
    magic[0] = 'V';
    EXPECT_NE(refusal_of_bytes(magic).find("does not begin with 'IBSP'"), std::string::npos);
    BspFile v47 = minimal_level();
    v47.version = 47;
    EXPECT_NE(refusal_of_bytes(v47.bytes()).find("version 47"), std::string::npos) << refusal_of_bytes(v47.bytes());
    EXPECT_NE(refusal_of_bytes({'I', 'B', 'S', 'P', 46, 0, 0, 0}).find("shorter than the header"), std::string::npos);
    // Lump 13 (faces): its directory entry at byte 8 + 13 * 8.
    auto with_entry = [&](int lump, std::int32_t offset, std::int32_t length) {
        std::vector<char> b = good;
        std::memcpy(b.data() + 8 + 8 * lump, &offset, 4);
        std::memcpy(b.data() + 12 + 8 * lump, &length, 4);
        return refusal_of_bytes(b);
    };
    const auto size = std::int32_t(good.size());
    EXPECT_NE(with_entry(13, size - 50, 104).find("lump 13 (faces): bytes"), std::string::npos) << with_entry(13, size - 50, 104);
    EXPECT_NE(with_entry(13, -4, 104).find("lump 13 (faces): a negative offset"), std::string::npos);
    EXPECT_NE(with_entry(10, 144, -44).find("lump 10 (vertexes): a negative"), std::string::npos);
    EXPECT_NE(with_entry(13, 144, 100).find("lump 13 (faces): 100 bytes are not whole records of 104"), std::string::npos);
    EXPECT_NE(with_entry(16, 144, 4).find("lump 16 (visdata): 4 bytes, fewer than its two counts"), std::string::npos);
}

TEST(Quake3Bsp, EveryTruncationIsRefusedNamingTheFile)
{
    const std::vector<char> good = minimal_level().bytes();
    ASSERT_EQ(refusal_of_bytes(good), "");
    // The last lump (visdata) ends the file; the entities lump's NUL is the
    // only byte a reader may do without, and it is the first lump.
    for (std::size_t n = 0; n < good.size(); ++n) {
        const std::string why = refusal_of_bytes(std::vector<char>(good.begin(), good.begin() + long(n)));
        EXPECT_EQ(why.rfind("cannot read scene 'test.bsp': Quake III BSP: ", 0), 0u) << n << " bytes: " << why;
    }
}

TEST(Quake3Bsp, IndicesOutsideTheirLumpsAreRefusedNamingLumpAndRecord)
{
    struct Case {
        const char *name;
        std::function<void(BspFile &)> change;
        const char *message;
    };
    const Case cases[] = {
        {"face texture", [](BspFile &f) { f.faces[1].texture = 5; }, "lump 13 (faces): record 1: texture 5 to 6 lie outside the 5 textures"},
        {"face texture negative", [](BspFile &f) { f.faces[1].texture = -1; }, "lump 13 (faces): record 1: texture -1"},
        {"face vertices", [](BspFile &f) { f.faces[0].vertex_count = 100; }, "lump 13 (faces): record 0: vertices 0 to 100 lie outside the"},
        {"face meshverts", [](BspFile &f) { f.faces[0].meshvert = 7; }, "lump 13 (faces): record 0: meshverts 7 to 13"},
        {"meshvert beyond its face", [](BspFile &f) { f.meshverts[1] = 4; }, "lump 13 (faces): record 0: meshvert 1 is 4, outside the face's 4 vertices"},
        {"meshvert negative", [](BspFile &f) { f.meshverts[1] = -1; }, "meshvert 1 is -1"},
        {"meshverts not triangles", [](BspFile &f) { f.faces[0].meshvert_count = 5; }, "record 0: 5 meshverts are not whole triangles"},
        {"face type", [](BspFile &f) { f.faces[0].type = 5; }, "lump 13 (faces): record 0: type 5 is none of"},
        {"patch even width", [](BspFile &f) { f.faces[2].width = 2; }, "lump 13 (faces): record 2: a patch of 2 x 3 control points"},
        {"patch size and vertices", [](BspFile &f) { f.faces[2].vertex_count = 8; }, "a patch of 3 x 3 control points"},
        {"node plane", [](BspFile &f) { f.nodes[0].plane = 1; }, "lump 3 (nodes): record 0: plane 1 to 2 lie outside the 1 planes"},
        {"node child leaf", [](BspFile &f) { f.nodes[0].back = -3; }, "lump 3 (nodes): record 0: child leaf 2 lies outside the 2 leafs"},
        {"node child cycle", [](BspFile &f) { f.nodes[0].front = 0; }, "lump 3 (nodes): record 0: child node 0 does not lie after it"},
        {"node child beyond", [](BspFile &f) { f.nodes[0].front = 1; }, "child node 1 does not lie after it among the 1 nodes"},
        {"leaf faces", [](BspFile &f) { f.leaves[1].leaf_face_count = 3; }, "lump 4 (leafs): record 1: leaf faces 3 to 6 lie outside the 5 leaffaces"},
        {"leaf brushes", [](BspFile &f) { f.leaves[0].leaf_brush_count = 1; }, "lump 4 (leafs): record 0: leaf brushes 0 to 1"},
        {"leaf cluster beyond visdata", [](BspFile &f) { f.leaves[0].cluster = 2; }, "lump 4 (leafs): record 0: cluster 2 is neither -1"},
        {"leaf cluster below -1", [](BspFile &f) { f.leaves[0].cluster = -2; }, "cluster -2 is neither"},
        {"leaf face", [](BspFile &f) { f.leaf_faces[4] = 7; }, "lump 5 (leaffaces): record 4: face 7 to 8 lie outside the 7 faces"},
        {"model faces", [](BspFile &f) { f.models[0].face_count = 8; }, "lump 7 (models): record 0: faces 0 to 8"},
        {"model faces overlap", [](BspFile &f) { f.models.push_back({6, 1}); }, "lump 7 (models): record 0: faces 0 to 7 overlap those of model 1"},
        {"visdata size", [](BspFile &f) { f.visdata[4] = 2; }, "lump 16 (visdata): 2 clusters of 2 bytes do not fit its 2 bytes"},
        {"visdata vector too short", [](BspFile &f) { f.visdata = {9, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1}; }, "vectors of 1 bytes cannot hold a bit for each of 9"},
        {"visdata negative", [](BspFile &f) { f.visdata[3] = char(0x80); }, "lump 16 (visdata): -2147483646 clusters"},
        {"nan vertex", [](BspFile &f) { f.vertices[5].position.y = std::numeric_limits<float>::quiet_NaN(); }, "lump 10 (vertexes): record 5: position (64.000000, nan, 64.000000) is not finite"},
        {"infinite vertex", [](BspFile &f) { f.vertices[9].position.z = std::numeric_limits<float>::infinity(); }, "lump 10 (vertexes): record 9: position"},
        {"brush sides", [](BspFile &f) { add_box_brush(f, {0, 0, 0}, {8, 8, 8}, 0, 0); f.brushes[0].side_count = 7; }, "lump 8 (brushes): record 0: brush sides 0 to 7 lie outside the 6 brushsides"},
        {"brush texture", [](BspFile &f) { add_box_brush(f, {0, 0, 0}, {8, 8, 8}, 0, 0); f.brushes[0].texture = 5; }, "lump 8 (brushes): record 0: texture 5 to 6"},
        {"brush side plane", [](BspFile &f) { add_box_brush(f, {0, 0, 0}, {8, 8, 8}, 0, 0); f.brush_sides[2].plane = 9; }, "lump 9 (brushsides): record 2: plane 9 to 10"},
        {"brush side plane not unit", [](BspFile &f) { add_box_brush(f, {0, 0, 0}, {8, 8, 8}, 0, 0); f.planes[3] = {0, 2, 0, 8}; }, "lump 2 (planes): record 3: a brush side's plane (normal length 2.000000"},
        {"brush side plane far", [](BspFile &f) { add_box_brush(f, {0, 0, 0}, {8, 8, 8}, 0, 0); f.planes[3].w = 1e30f; }, "is not a unit normal within 2^20 units"},
        {"nan plane", [](BspFile &f) { f.planes[0].w = std::numeric_limits<float>::quiet_NaN(); }, "lump 2 (planes): record 0: a normal or distance that is not finite"},
        {"no face drawn", [](BspFile &f) { for (auto &face : f.faces) face.texture = 1; }, "lump 13 (faces): none of its 7 faces is drawn"},
        {"entity unclosed", [](BspFile &f) { f.entities += "{ \"classname\" \"x\""; }, "lump 0 (entities): at byte"},
        {"entity unquoted", [](BspFile &f) { f.entities += "{ classname x }"; }, "a key or value does not begin with '\"'"},
        {"entity string open", [](BspFile &f) { f.entities += "{ \"classname"; }, "without its closing '\"'"},
        {"entity stray", [](BspFile &f) { f.entities += "}"; }, "expected '{' opening an entity"},
        {"spawn origin", [](BspFile &f) { f.entities += "{ \"classname\" \"info_player_start\" \"origin\" \"1 2\" }"; }, "entity 4 (info_player_start): origin '1 2' is not three finite numbers"},
        {"spawn origin nan", [](BspFile &f) { f.entities += "{ \"classname\" \"info_player_start\" \"origin\" \"1 nan 2\" }"; }, "origin '1 nan 2'"},
        {"spawn angle", [](BspFile &f) { f.entities += "{ \"classname\" \"info_player_start\" \"angle\" \"inf\" }"; }, "angle 'inf' is not a finite number"},
    };
    for (const Case &c : cases) {
        const std::string why = refusal_of(c.change);
        EXPECT_EQ(why.rfind("cannot read scene 'test.bsp': Quake III BSP: ", 0), 0u) << c.name << ": " << why;
        EXPECT_NE(why.find(c.message), std::string::npos) << c.name << ": " << why;
    }
}

TEST(Quake3Bsp, FacesSharingTheirRecordsCannotMakeUnboundedGeometry)
{
    // 1,000 patches on the same 9 control points at 64 segments: 4.2
    // million vertices from a file of a tenth of a megabyte.
    BspFile patches = minimal_level();
    patches.faces.resize(1000, patches.faces[2]);
    patches.models = {{0, 1000}};
    std::vector<std::string> warnings;
    try {
        read_quake3_bsp("test.bsp", patches.bytes(), Quake3Options{64}, warnings);
        FAIL() << "1,000 patches of 64 x 64 quads read";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("segments a piece make more than 4194304 vertices"), std::string::npos) << e.what();
    }
    // 6,000 faces sharing 3,000 meshverts: 6 million triangles from a file of 0.6 megabytes.
    BspFile meshes = minimal_level();
    meshes.vertices.resize(3);
    meshes.meshverts.assign(3000, 0);
    for (std::size_t k = 0; k < meshes.meshverts.size(); ++k)
        meshes.meshverts[k] = std::int32_t(k % 3);
    meshes.faces.assign(6000, {0, 3, 0, 3, 0, 3000, {0, 0, 1}});
    meshes.models = {{0, 6000}};
    meshes.leaf_faces = {0, 1, 2, 3, 4};
    const std::string why = refusal_of_bytes(meshes.bytes());
    EXPECT_NE(why.find("the faces so far make more than 4194304 triangles"), std::string::npos) << why;
}

TEST(Quake3Bsp, PatchSegmentsOutsideTheirRangeAreRefused)
{
    for (int segments : {0, 65})
        EXPECT_THROW(read(minimal_level(), Quake3Options{segments}), std::runtime_error) << segments;
}

TEST(Quake3Bsp, ZeroNormalsAreReplacedWithAWarning)
{
    BspFile f = minimal_level();
    f.vertices[0].normal = glm::vec3(0.0f);
    std::vector<std::string> warnings;
    const Scene s = read_quake3_bsp("test.bsp", f.bytes(), {}, warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("test.bsp"), std::string::npos) << warnings[0];
    // The floor's vertex 0 with the floor's own normal, up.
    const Mesh &wall = *mesh_named(s, "textures/test/wall");
    expect_near(wall.normals[0], {0, 1, 0});
}

namespace {

// A zip file at `path` holding `member` with `bytes`, through libzip.
void write_pk3(const std::string &path, const std::string &member, const std::vector<char> &bytes)
{
    int error = 0;
    zip_t *z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    ASSERT_NE(z, nullptr);
    zip_source_t *source = zip_source_buffer(z, bytes.data(), bytes.size(), 0);
    ASSERT_NE(source, nullptr);
    ASSERT_GE(zip_file_add(z, member.c_str(), source, ZIP_FL_OVERWRITE), 0);
    ASSERT_EQ(zip_close(z), 0);
}

std::string load_refusal(const std::string &name)
{
    try {
        load_scene(name);
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Quake3Bsp, LoadSceneReadsALevelFromAPk3OrAFile)
{
    const std::vector<char> bytes = minimal_level().bytes();
    const std::string pk3 = temp("level.pk3"), bsp = temp("level.bsp");
    write_pk3(pk3, "maps/test.bsp", bytes);
    {
        std::ofstream f(bsp, std::ios::binary);
        f.write(bytes.data(), std::streamsize(bytes.size()));
    }
    for (const std::string &name : {pk3 + ":maps/test.bsp", pk3 + ":MAPS/Test.BSP", bsp}) {
        const Scene s = load_scene(name);
        // Wall (polygon, mesh, patch), glass and sky.
        EXPECT_EQ(s.triangle_count(), 3u + 128u + 2u + 2u) << name;
        ASSERT_TRUE(s.level) << name;
        EXPECT_EQ(s.level->spawns.size(), 2u) << name;
    }
    Quake3Options coarse;
    coarse.patch_segments = 2;
    EXPECT_EQ(load_scene(bsp, nullptr, coarse).triangle_count(), 3u + 8u + 2u + 2u);

    // Missing archive, missing member, malformed member, not a zip file.
    std::string why = load_refusal(pk3 + ":maps/other.bsp");
    EXPECT_NE(why.find("holds no member 'maps/other.bsp'"), std::string::npos) << why;
    EXPECT_NE(why.find("maps/test.bsp"), std::string::npos) << "the levels it does hold: " << why;
    why = load_refusal(temp("missing.pk3") + ":maps/test.bsp");
    EXPECT_NE(why.find("cannot open the archive '" + temp("missing.pk3") + "'"), std::string::npos) << why;
    std::vector<char> broken = bytes;
    broken[8 + 8 * 13 + 4] = 99;   // the faces lump's length
    write_pk3(pk3, "maps/test.bsp", broken);
    why = load_refusal(pk3 + ":maps/test.bsp");
    EXPECT_NE(why.find("cannot read scene '" + pk3 + ":maps/test.bsp': Quake III BSP: lump 13 (faces)"), std::string::npos) << why;
    {
        std::ofstream f(pk3);
        f << "not a zip file\n";
    }
    why = load_refusal(pk3 + ":maps/test.bsp");
    EXPECT_NE(why.find("cannot open the archive '" + pk3 + "'"), std::string::npos) << why;
    why = load_refusal(temp("missing.bsp"));
    EXPECT_NE(why.find("cannot read scene '" + temp("missing.bsp") + "'"), std::string::npos) << why;
    std::remove(pk3.c_str());
    std::remove(bsp.c_str());
}

// One of Debian's OpenArena levels (tools/deps.sh test installs
// openarena-088-data): a small arena of a few thousand triangles.
TEST(Quake3Bsp, OpenArenaLevelFromDebian)
{
    const std::string pk3 = "/usr/share/games/openarena/baseoa/pak6-patch088.pk3";
    ASSERT_TRUE(std::ifstream(pk3).good()) << pk3 << " is missing: tools/deps.sh test installs openarena-088-data";
    const Scene s = load_scene(pk3 + ":maps/aggressor.bsp");
    ASSERT_TRUE(s.level);
    const Level &level = *s.level;
    EXPECT_GT(s.triangle_count(), 1000u);
    EXPECT_LT(s.triangle_count(), 1000000u);
    // A player is about 1.4 m tall in the level's metres; an arena is tens of metres across.
    const glm::vec3 extent = s.bounds.extent();
    EXPECT_GT(std::min(extent.x, extent.z), 10.0f);
    EXPECT_LT(std::max({extent.x, extent.y, extent.z}), 1000.0f);
    ASSERT_FALSE(level.spawns.empty());
    for (const LevelSpawn &spawn : level.spawns) {
        EXPECT_TRUE(s.bounds.contains(spawn.eye));
        const std::int32_t leaf = level.leaf_at(spawn.eye);
        ASSERT_GE(leaf, 0);
        EXPECT_GE(level.leaves[std::size_t(leaf)].cluster, 0) << "a spawn eye in a solid leaf";
    }
    // The compiler's PVS: a cluster sees itself; every leaf's cluster is one of it.
    ASSERT_GT(level.cluster_count, 0);
    EXPECT_GE(level.bytes_per_cluster * 8, level.cluster_count);
    for (std::int32_t c = 0; c < level.cluster_count; ++c)
        EXPECT_TRUE(level.cluster_sees(c, c)) << "cluster " << c;
    std::size_t open = 0;
    for (const Level::Leaf &leaf : level.leaves) {
        EXPECT_LT(leaf.cluster, level.cluster_count);
        open += leaf.cluster >= 0;
    }
    EXPECT_GT(open, 0u);
    // Every drawn face's triangles lie in its mesh.
    for (const Level::Face &face : level.faces) {
        if (face.mesh >= 0) {
            EXPECT_LE(face.first_index + face.index_count, s.meshes[std::size_t(face.mesh)].indices.size());
        }
    }
}

namespace {

// A w x h TGA (uncompressed true colour, top row first) of one RGB colour.
std::vector<char> tga(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b)
{
    std::vector<char> out = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, char(w), char(w >> 8), char(h), char(h >> 8), 24, 0x20};
    for (int i = 0; i < w * h; ++i)
        out.insert(out.end(), {char(b), char(g), char(r)});
    return out;
}

void write_pk3_members(const std::string &path, const std::vector<std::pair<std::string, std::vector<char>>> &members)
{
    int error = 0;
    zip_t *z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    ASSERT_NE(z, nullptr);
    for (const auto &[name, bytes] : members) {
        zip_source_t *source = zip_source_buffer(z, bytes.data(), bytes.size(), 0);
        ASSERT_NE(source, nullptr);
        ASSERT_GE(zip_file_add(z, name.c_str(), source, ZIP_FL_OVERWRITE), 0);
    }
    ASSERT_EQ(zip_close(z), 0);
}

}  // namespace

TEST(Quake3Bsp, TheLookReadsCoordinatesVertexLightAndPictures)
{
    // Two paks in a directory of their own: the later one's wall replaces
    // the earlier one's; the glass's shader names its picture as .jpg in its
    // second stage (the first draws the lightmap), which is found as .tga.
    const std::string dir = temp("look");
    std::filesystem::create_directories(dir);
    const std::string shader = "// a comment\ntextures/test/glass\n{\n  surfaceparm trans\n  {\n    map $lightmap\n  }\n"
                               "  {\n    map textures/test/pane.jpg\n    blendfunc add\n  }\n}\n";
    write_pk3_members(dir + "/pak0.pk3", {{"maps/test.bsp", minimal_level().bytes()},
                                          {"textures/test/wall.tga", tga(2, 1, 255, 0, 0)},
                                          {"scripts/test.shader", std::vector<char>(shader.begin(), shader.end())},
                                          {"textures/test/pane.tga", tga(1, 1, 0, 0, 255)}});
    write_pk3_members(dir + "/pak1.pk3", {{"textures/test/wall.tga", tga(2, 2, 0, 255, 0)}});

    Quake3Options look;
    look.look = true;
    std::vector<std::string> warnings;
    const Scene s = load_scene(dir + "/pak0.pk3:maps/test.bsp", &warnings, look);
    const Mesh *wall = mesh_named(s, "textures/test/wall"), *glass = mesh_named(s, "textures/test/glass"),
               *sky = mesh_named(s, "textures/skies/sky");
    ASSERT_TRUE(wall && glass && sky);
    for (const Mesh *m : {wall, glass, sky}) {
        EXPECT_EQ(m->texcoords.size(), m->positions.size()) << m->name;
        EXPECT_EQ(m->vertex_light.size(), m->positions.size()) << m->name;
        EXPECT_FALSE(m->lightmapped) << m->name << ": the faces name no lightmap";
        // The file's white vertex colour, doubled and held at white.
        for (std::uint32_t v : m->vertex_light)
            EXPECT_EQ(v, 0xffffffffu) << m->name;
    }
    EXPECT_EQ(s.lightmap_atlas, -1) << "the level has no lightmaps";
    ASSERT_GE(wall->image, 0);
    const Image &w = s.images[std::size_t(wall->image)];
    EXPECT_EQ(w.width, 2);
    EXPECT_EQ(w.height, 2) << "the later pak's picture";
    EXPECT_EQ(int(w.rgba[1]), 255);
    ASSERT_GE(glass->image, 0);
    const Image &g = s.images[std::size_t(glass->image)];
    EXPECT_EQ(g.name, "textures/test/pane.tga");
    EXPECT_EQ(int(g.rgba[2]), 255);
    EXPECT_EQ(sky->image, -1) << "the sky keeps its colour";
    EXPECT_EQ(s.images.size(), 2u) << "only the pictures a mesh uses";
    EXPECT_TRUE(warnings.empty());

    // Without the look, none of it is read.
    const Scene flat = load_scene(dir + "/pak0.pk3:maps/test.bsp");
    EXPECT_TRUE(flat.images.empty());
    EXPECT_TRUE(mesh_named(flat, "textures/test/wall")->texcoords.empty());

    // A texture found nowhere is named in a warning and drawn without a picture.
    write_pk3_members(dir + "/pak1.pk3", {{"textures/other/thing.tga", tga(1, 1, 1, 2, 3)}});
    write_pk3_members(dir + "/pak0.pk3", {{"maps/test.bsp", minimal_level().bytes()}});
    warnings.clear();
    const Scene bare = load_scene(dir + "/pak0.pk3:maps/test.bsp", &warnings, look);
    EXPECT_EQ(mesh_named(bare, "textures/test/wall")->image, -1);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("textures/test/wall"), std::string::npos) << warnings[0];
    std::filesystem::remove_all(dir);
}
