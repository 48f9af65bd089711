// SPDX-License-Identifier: MIT
#include "scene/scene_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/png.h"

using namespace occu;

namespace {
std::string temp(const char *name)
{
    return ::testing::TempDir() + "occu_" + std::to_string(getpid()) + "_" + name;
}
}  // namespace

TEST(LoadScene, ObjQuadBecomesTwoTriangles)
{
    const std::string path = temp("quad.obj");
    {
        std::ofstream f(path);
        f << "v 0 0 0\nv 2 0 0\nv 2 3 0\nv 0 3 0\nf 1 2 3 4\n";
    }
    const Scene s = load_scene(path);
    std::remove(path.c_str());
    ASSERT_EQ(s.triangle_count(), 2u);
    EXPECT_FLOAT_EQ(s.bounds.max.x, 2.0f);
    EXPECT_FLOAT_EQ(s.bounds.max.y, 3.0f);
    EXPECT_EQ(s.meshes[0].normals.size(), s.meshes[0].positions.size());
}

// A triangle whose corners are collinear to float precision has no
// surface; a model's are left out as a level's are
// (Quake3Bsp.TrianglesWithCollinearCornersAreLeftOut says why).
TEST(LoadScene, ObjTrianglesWithCollinearCornersAreLeftOut)
{
    const std::string path = temp("collinear.obj");
    {
        std::ofstream f(path);
        f << "v 0 0 0\nv 2 0 0\nv 2 3 0\nv 0 3 0\n"
             "v 0.1 0.2 0.3\nv 10.1 20.2 30.3\nv 5.1 10.2 15.3\n"
             "f 1 2 3 4\nf 5 6 7\n";
    }
    const Scene s = load_scene(path);
    std::remove(path.c_str());
    EXPECT_EQ(s.triangle_count(), 2u) << "the quad's two, not the collinear one";
    std::size_t collinear = 0;
    for (const Mesh &m : s.meshes)
        for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]),
                c(m.positions[m.indices[t + 2]]);
            const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
            collinear += glm::length(glm::cross(b - a, c - a)) <= longest * 31.0 * 1.2e-7;
        }
    EXPECT_EQ(collinear, 0u);
}

TEST(LoadScene, ErrorsNameTheFile)
{
    const std::string bad = temp("bad.obj");
    {
        std::ofstream f(bad);
        f << "this is not a scene\n";
    }
    for (const std::string &path : {bad, std::string("/nonexistent/scene.gltf")}) {
        try {
            load_scene(path);
            FAIL() << "no exception for " << path;
        } catch (const std::runtime_error &e) {
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        }
    }
    std::remove(bad.c_str());
}

namespace {
// What load_scene says when it refuses `path`, or "" when it loads it.
std::string refusal_of(const std::string &path)
{
    try {
        load_scene(path);
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(LoadScene, InfiniteVertexIsRefusedNamingFileMeshAndVertex)
{
    // 1e39 is beyond float range: the importer reads it as infinity.
    const std::string path = temp("infinite.obj");
    {
        std::ofstream f(path);
        f << "o wall\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 1e39 1 0\nf 1 2 3\nf 1 3 4\n";
    }
    const std::string message = refusal_of(path);
    std::remove(path.c_str());
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("'wall'"), std::string::npos) << message;
    EXPECT_NE(message.find("vertex"), std::string::npos) << message;
    EXPECT_NE(message.find("not finite"), std::string::npos) << message;
}

TEST(LoadScene, NanVertexIsRefusedNamingFileMeshAndVertex)
{
    const std::string path = temp("nan.obj");
    {
        std::ofstream f(path);
        f << "o wall\nv 0 0 0\nv 1 0 0\nv 1 nan 0\nf 1 2 3\n";
    }
    const std::string message = refusal_of(path);
    std::remove(path.c_str());
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("'wall'"), std::string::npos) << message;
    EXPECT_NE(message.find("nan"), std::string::npos) << message;
}

TEST(LoadScene, MaterialColoursArePaletteHuesWhereTheFileHasNone)
{
    const std::string obj = temp("colours.obj"), mtl = temp("colours.mtl");
    {
        std::ofstream f(mtl);
        f << "newmtl blue\nKd 0.2 0.4 0.6\nnewmtl broken\nKd nan 0.5 2\n";
    }
    {
        std::ofstream f(obj);
        f << "mtllib " << mtl.substr(mtl.find_last_of('/') + 1) << "\n"
          << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
          << "o coloured\nusemtl blue\nf 1 2 3\n"
          << "o broken\nusemtl broken\nf 1 3 4\n";
    }
    const std::string plain = temp("plain.obj");
    {
        std::ofstream f(plain);
        f << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\no a\nf 1 2 3\no b\nf 1 3 4\n";
    }
    const std::string painted = temp("painted.obj");
    {
        std::ofstream f(painted);
        f << "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nf 1 2 3\n";
    }
    const Scene s = load_scene(obj), p = load_scene(plain), v = load_scene(painted);
    for (const std::string &path : {obj, mtl, plain, painted})
        std::remove(path.c_str());

    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_FLOAT_EQ(s.meshes[0].color.r, 0.2f);
    EXPECT_FLOAT_EQ(s.meshes[0].color.g, 0.4f);
    EXPECT_FLOAT_EQ(s.meshes[0].color.b, 0.6f);
    // A colour that is not a number or out of range becomes a usable one.
    for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(std::isfinite(s.meshes[1].color[k]));
        EXPECT_GE(s.meshes[1].color[k], 0.0f);
        EXPECT_LE(s.meshes[1].color[k], 1.0f);
    }
    // No material: each mesh a hue of its own, not the importer's grey.
    ASSERT_EQ(p.meshes.size(), 2u);
    EXPECT_NE(p.meshes[0].color, p.meshes[1].color);
    for (const Mesh &m : p.meshes)
        EXPECT_FALSE(m.color.r == m.color.g && m.color.g == m.color.b) << "a grey";
    // Vertex colours, one per position.
    ASSERT_EQ(v.meshes.size(), 1u);
    const Mesh &m = v.meshes[0];
    ASSERT_EQ(m.colors.size(), m.positions.size());
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        const glm::vec3 expected = m.positions[i] == glm::vec3(0, 0, 0)   ? glm::vec3(1, 0, 0)
                                   : m.positions[i] == glm::vec3(1, 0, 0) ? glm::vec3(0, 1, 0)
                                                                          : glm::vec3(0, 0, 1);
        EXPECT_EQ(m.colors[i], expected) << "vertex " << i;
    }
}

// The scene-file fuzzer's findings (tests/fuzz/scene_file_fuzz.cpp), each
// refused or dropped with a message naming the file.

namespace {
void write(const std::string &path, const std::string &text)
{
    std::ofstream f(path, std::ios::binary);
    f << text;
}

// A glTF file of one triangle (three VEC3 floats in a data URI) with
// `accessor` for its positions accessor and `primitive` for its primitive.
std::string gltf(const std::string &accessor, const std::string &primitive)
{
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
           R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
           R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],)"
           R"("bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[)" +
           accessor + R"(],"meshes":[{"name":"tri","primitives":[)" + primitive + "]}]}";
}
const std::string triangle_accessor = R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"})";
}  // namespace

TEST(LoadScene, GltfTriangleLoads)
{
    const std::string path = temp("triangle.gltf");
    write(path, gltf(triangle_accessor, R"({"attributes":{"POSITION":0}})"));
    std::vector<std::string> warnings;
    const Scene s = load_scene(path, &warnings);
    std::remove(path.c_str());
    ASSERT_EQ(s.triangle_count(), 1u);
    EXPECT_FLOAT_EQ(s.bounds.max.x, 1.0f);
    EXPECT_TRUE(warnings.empty());
}

// assimp 5.2.5 checks an accessor's count against its view's length but
// not its offset: it read 12 bytes past the buffer (ASan: heap overflow).
TEST(LoadScene, GltfAccessorPastItsBufferViewIsRefused)
{
    const std::string path = temp("overflow.gltf");
    write(path, gltf(R"({"bufferView":0,"byteOffset":12,"componentType":5126,"count":3,"type":"VEC3"})",
                     R"({"attributes":{"POSITION":0}})"));
    const std::string message = refusal_of(path);
    std::remove(path.c_str());
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("accessor 0"), std::string::npos) << message;
    EXPECT_NE(message.find("runs past the end of buffer view 0"), std::string::npos) << message;
}

// assimp 5.2.5 makes count - 2 faces of a triangle fan or strip: for a fan
// of no vertices it asked for 2^32 - 2 faces (64 GB; ASan: out of memory);
// of 2, 2^64 - 1.
TEST(LoadScene, GltfFanOfTooFewVerticesIsRefused)
{
    for (const char *mode : {"5", "6"}) {
        const std::string path = temp("fan.gltf");
        write(path, gltf(R"({"bufferView":0,"componentType":5126,"count":2,"type":"VEC3"})",
                         std::string(R"({"attributes":{"POSITION":0},"mode":)") + mode + "}"));
        const std::string message = refusal_of(path);
        std::remove(path.c_str());
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_NE(message.find("mesh 0 primitive 0 (mode " + std::string(mode) + ") has 2 vertices; it needs 3"),
                  std::string::npos)
            << message;
    }
}

// assimp 5.2.5 closed an indexed line loop with its first face, which it
// had dropped (no positions): a null dereference (the fuzzer: SEGV).
TEST(LoadScene, GltfPrimitiveWithoutPositionsOrIndexedLineLoopIsRefused)
{
    const std::string path = temp("loop.gltf");
    const std::string indices = R"(,{"bufferView":0,"componentType":5125,"count":3,"type":"SCALAR"})";
    for (const std::string &primitive : {std::string(R"({"attributes":{"NORMAL":0},"indices":1,"mode":2})"),
                                         std::string(R"({"attributes":{"POSITION":0},"indices":1,"mode":2})")}) {
        write(path, gltf(triangle_accessor + indices, primitive));
        const std::string message = refusal_of(path);
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_NE(message.find("mesh 0 primitive 0"), std::string::npos) << message;
    }
    std::remove(path.c_str());
}

TEST(LoadScene, GltfOneOnlyAndBrokenJsonAreRefused)
{
    const std::string path = temp("old.gltf");
    for (const std::string &text : {std::string(R"({"asset":{"version":"1.0"}})"), std::string("{\"asset\":"),
                                    std::string(200, '[')}) {
        write(path, text);
        const std::string message = refusal_of(path);
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_NE(message.find("glTF"), std::string::npos) << message;
    }
    std::remove(path.c_str());
}

// assimp 5.2.5's PLY header parser loops forever at the end of a file
// without an end_header line (the fuzzer: a timeout).
TEST(LoadScene, PlyHeaderWithoutEndIsRefused)
{
    const std::string path = temp("truncated.ply");
    write(path, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n");
    const std::string message = refusal_of(path);
    std::remove(path.c_str());
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("end_header"), std::string::npos) << message;
}

TEST(LoadScene, PlyTriangleLoads)
{
    const std::string path = temp("triangle.ply");
    write(path, "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\nproperty float y\r\n"
                "property float z\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
                "0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n");
    const Scene s = load_scene(path);
    std::remove(path.c_str());
    EXPECT_EQ(s.triangle_count(), 1u);
}

// A node that scales by zero has no inverse for its normals: they were
// NaN, and used.
TEST(LoadScene, NormalsNotFiniteAreReplacedWithAWarning)
{
    const std::string path = temp("flattened.gltf");
    std::string text = gltf(triangle_accessor, R"({"attributes":{"POSITION":0}})");
    // Flattened along z: the triangle (in the xy plane) keeps its surface,
    // its normals through the inverse transpose are not finite.
    const std::string node = R"("nodes":[{"mesh":0})";
    text.replace(text.find(node), node.size(), R"("nodes":[{"mesh":0,"scale":[1,1,0]})");
    write(path, text);
    std::vector<std::string> warnings;
    const Scene s = load_scene(path, &warnings);
    std::remove(path.c_str());
    ASSERT_EQ(s.meshes.size(), 1u);
    for (const glm::vec3 &n : s.meshes[0].normals)
        EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find(path), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("'tri'"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("3 of its 3 normals"), std::string::npos) << warnings[0];
}

// Points and lines were dropped without a word.
TEST(LoadScene, LinesAreDroppedWithAWarning)
{
    const std::string path = temp("lines.obj");
    write(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\no tri\nf 1 2 3\no wire\nl 1 2\nl 2 3\n");
    std::vector<std::string> warnings;
    const Scene s = load_scene(path, &warnings);
    std::remove(path.c_str());
    EXPECT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find(path), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("'wire'"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("holds 2 points or lines"), std::string::npos) << warnings[0];
}

namespace {
std::string ply_triangle(const std::string &vertices, const std::string &face)
{
    return "ply\nformat ascii 1.0\nelement vertex " + vertices +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
           "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n" + face + "\n";
}
}  // namespace

// assimp 5.2.5's PLY importer keeps a face's indices unchecked; its normal
// generation then read far past the vertices (the fuzzer: a SEGV).
TEST(LoadScene, PlyFaceBeyondItsVerticesIsRefused)
{
    const std::string path = temp("beyond.ply");
    write(path, ply_triangle("3", "3 0 1 7"));
    const std::string message = refusal_of(path);
    std::remove(path.c_str());
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("1 of its 1 faces index beyond its 3 vertices"), std::string::npos) << message;
}

// "element vertex 4294967295": assimp allocates that many vertices (48 GB)
// and loops as many times, whatever the file holds.
TEST(LoadScene, PlyCountsBeyondTheFileAreRefused)
{
    const std::string path = temp("huge.ply");
    for (const char *count : {"4294967295", "99999999999"}) {
        write(path, ply_triangle(count, "3 0 1 2"));
        const std::string message = refusal_of(path);
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_NE(message.find("PLY"), std::string::npos) << message;
    }
    std::remove(path.c_str());
}

// A header assimp 5.2.5 reads leniently: misspelt keywords, a second
// header inside the first, an unknown type or format. assimp misread one
// such ASCII file and freed memory it never allocated (the fuzzer:
// regression-two-headers.ply); every line of a header must be PLY's.
TEST(LoadScene, PlyHeaderOutsidePlysGrammarIsRefused)
{
    const std::string path = temp("grammar.ply");
    const std::string good = ply_triangle("3", "3 0 1 2");
    const std::pair<std::string, std::string> bad[] = {
        {"element vertex", "ele~ment vertex"},   // then its properties follow no element
        {"property float y", "property floap32 y"},
        {"format ascii 1.0", "format ascii 1\xfe"},
        {"format ascii 1.0", "format text 1.0"},
        {"ply\n", "plz\n"},
        {"element face 1\n", "element face 1\nply\n"},
        {"element face 1", "element 2147483647face 1"},
        {"property float x", "property float 9x"},
    };
    for (const auto &[from, to] : bad) {
        std::string text = good;
        text.replace(text.find(from), from.size(), to);
        write(path, text);
        const std::string message = refusal_of(path);
        EXPECT_NE(message.find(path), std::string::npos) << to << ": " << message;
    }
    write(path, good);
    EXPECT_EQ(load_scene(path).triangle_count(), 1u);
    // A comment without 'comment', as old Blender exporters wrote (assimp's
    // Wuson.ply): read as a comment, with a warning naming the file and line.
    std::string blender = good;
    blender.replace(blender.find("element vertex"), 0, "Created by Blender3D 247 - www.blender.org\n");
    write(path, blender);
    std::vector<std::string> warnings;
    EXPECT_EQ(load_scene(path, &warnings).triangle_count(), 1u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find(path), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("'Created by Blender3D 247"), std::string::npos) << warnings[0];
    std::remove(path.c_str());
}

// ASCII data read as the header lays it out, a line an instance: assimp
// 5.2.5 sizes a list by its length before reading it and reads on past a
// short line (the fuzzer: allocations of 2.9 and 27 GB).
TEST(LoadScene, PlyAsciiDataOutsideItsLayoutIsRefused)
{
    const std::string path = temp("ascii-layout.ply");
    for (const char *face : {"3 0 1", "4294967295 0 1 2", "3.5 0 1 2", "x 0 1 2"}) {
        write(path, ply_triangle("3", face));
        const std::string message = refusal_of(path);
        EXPECT_NE(message.find(path), std::string::npos) << face << ": " << message;
        EXPECT_NE(message.find("PLY: data line 4"), std::string::npos) << face << ": " << message;
    }
    std::string short_vertex = ply_triangle("3", "3 0 1 2");
    short_vertex.replace(short_vertex.find("1 0 0\n"), 6, "1 0\n");
    write(path, short_vertex);
    const std::string message = refusal_of(path);
    EXPECT_NE(message.find("PLY: data line 2"), std::string::npos) << message;
    std::remove(path.c_str());
}

// A face of no indices (PLY "0"): assimp 5.2.5's later steps took the
// importer's faces for granted (the fuzzer: aborts and SIGBUS in them).
TEST(LoadScene, PlyFaceOfNoIndicesIsRefused)
{
    const std::string path = temp("empty-face.ply");
    write(path, ply_triangle("3", "0"));
    const std::string message = refusal_of(path);
    std::remove(path.c_str());
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("1 of its 1 faces have no indices"), std::string::npos) << message;
}

namespace {
// A binary PLY triangle; its face's list of `items` indices, of which the
// file holds `held`.
std::string binary_ply(unsigned char items, int held)
{
    std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    s.append(reinterpret_cast<const char *>(v), sizeof(v));
    s += char(items);
    for (int i = 0; i < held; ++i) {
        const std::int32_t index = i;
        s.append(reinterpret_cast<const char *>(&index), 4);
    }
    return s;
}
}  // namespace

// assimp 5.2.5 reads binary PLY data by the header without bounds: a list
// longer than the file read past its buffer (the fuzzer: a SEGV).
TEST(LoadScene, BinaryPlyListPastTheEndIsRefused)
{
    const std::string path = temp("binary.ply");
    write(path, binary_ply(3, 3));
    EXPECT_EQ(load_scene(path).triangle_count(), 1u);
    write(path, binary_ply(200, 3));
    const std::string message = refusal_of(path);
    std::remove(path.c_str());
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("a list of 200 items in instance 0 of element 1 runs past the end"), std::string::npos)
        << message;
}

// A model's look (quake3.look): its materials' diffuse pictures.

namespace {
// A 4x4 picture whose quadrants (2x2 texels each) are one colour: top left,
// top right, bottom left, bottom right; top row first.
const std::uint8_t quadrant_colours[4][4] = {{220, 30, 30, 255}, {30, 200, 40, 255}, {40, 50, 210, 255}, {230, 220, 60, 255}};
std::vector<std::uint8_t> quadrant_picture()
{
    std::vector<std::uint8_t> rgba;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const std::uint8_t *c = quadrant_colours[(y >= 2 ? 2 : 0) + (x >= 2 ? 1 : 0)];
            rgba.insert(rgba.end(), c, c + 4);
        }
    return rgba;
}

Quake3Options with_look()
{
    Quake3Options o;
    o.look = true;
    return o;
}
}  // namespace

TEST(LoadScene, ModelLookDecodesEachShownPictureOnceWithItsCoordinates)
{
    const std::string dir = temp("look_dir");
    std::filesystem::create_directories(dir + "/pictures");
    const std::vector<std::uint8_t> picture = quadrant_picture();
    write_png(dir + "/pictures/quads.png", 4, 4, picture.data(), false);
    // "painted" and "windows" name the same file (the second as a model
    // made on Windows may: from the drive's root, with its separators, the
    // file name in another case); "unused" names a missing one that no face
    // uses; "bare" has no picture.
    write(dir + "/m.mtl", "newmtl painted\nKd 0.5 0.25 1.0\nmap_Kd pictures/quads.png\n"
                          "newmtl windows\nKd 1 1 1\nmap_Kd \\pictures\\QUADS.png\n"
                          "newmtl unused\nKd 1 1 1\nmap_Kd nowhere-at-all.png\n"
                          "newmtl bare\nKd 0.3 0.6 0.9\n");
    // Texture coordinates (x, y) at position (x, y, z), so what each vertex
    // must carry is known from its position alone.
    write(dir + "/m.obj", "mtllib m.mtl\n"
                          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.25 0.75 1\n"
                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.25 0.75\n"
                          "o a\nusemtl painted\nf 1/1 2/2 3/3\n"
                          "o b\nusemtl windows\nf 1/1 3/3 4/4\n"
                          "o c\nusemtl bare\nf 1/1 2/2 5/5\n");
    std::vector<std::string> warnings;
    const Scene s = load_scene(dir + "/m.obj", &warnings, with_look());
    std::vector<std::string> flat_warnings;
    const Scene flat = load_scene(dir + "/m.obj", &flat_warnings);
    std::filesystem::remove_all(dir);

    EXPECT_TRUE(warnings.empty()) << "the unused material's picture is never looked for: " << warnings.front();
    ASSERT_EQ(s.images.size(), 1u) << "one file, decoded once";
    EXPECT_EQ(s.images[0].width, 4);
    EXPECT_EQ(s.images[0].height, 4);
    EXPECT_EQ(s.images[0].rgba, picture) << "top row first, as written";
    ASSERT_EQ(s.meshes.size(), 3u);
    for (const Mesh &m : s.meshes) {
        if (m.name == "c") {
            EXPECT_EQ(m.image, -1);
            EXPECT_TRUE(m.texcoords.empty());
            EXPECT_EQ(m.color, glm::vec3(0.3f, 0.6f, 0.9f));
            continue;
        }
        EXPECT_EQ(m.image, 0) << m.name;
        ASSERT_EQ(m.texcoords.size(), m.positions.size()) << m.name;
        for (std::size_t i = 0; i < m.positions.size(); ++i) {
            // assimp's v runs up from the picture's bottom; the picture is
            // uploaded top row first, so the look's t is 1 - v.
            EXPECT_FLOAT_EQ(m.texcoords[i].x, m.positions[i].x) << m.name << " vertex " << i;
            EXPECT_FLOAT_EQ(m.texcoords[i].y, 1.0f - m.positions[i].y) << m.name << " vertex " << i;
        }
        EXPECT_EQ(m.color, m.name == "a" ? glm::vec3(0.5f, 0.25f, 1.0f) : glm::vec3(1.0f)) << m.name;
    }
    // Without the look nothing is decoded and no coordinates kept.
    EXPECT_TRUE(flat_warnings.empty());
    EXPECT_TRUE(flat.images.empty());
    for (const Mesh &m : flat.meshes) {
        EXPECT_TRUE(m.texcoords.empty());
        EXPECT_EQ(m.image, -1);
    }
}

TEST(LoadScene, ModelPictureThatCannotBeReadIsNamedAndItsMeshKeepsItsColour)
{
    const std::string dir = temp("look_bad");
    std::filesystem::create_directories(dir);
    write(dir + "/garbage.png", "not a picture at all");
    write(dir + "/m.mtl", "newmtl gone\nKd 0.2 0.4 0.6\nmap_Kd missing-picture.jpg\n"
                          "newmtl broken\nKd 0.6 0.4 0.2\nmap_Kd garbage.png\n");
    write(dir + "/m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                          "o gone\nusemtl gone\nf 1/1 2/2 3/3\no broken\nusemtl broken\nf 1/1 3/3 4/4\n");
    std::vector<std::string> warnings;
    Scene s;
    ASSERT_NO_THROW(s = load_scene(dir + "/m.obj", &warnings, with_look()));
    std::filesystem::remove_all(dir);

    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("missing-picture.jpg"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("no such file"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("garbage.png"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("m.obj"), std::string::npos) << "names the model: " << warnings[0];
    EXPECT_TRUE(s.images.empty());
    ASSERT_EQ(s.meshes.size(), 2u);
    for (const Mesh &m : s.meshes) {
        EXPECT_EQ(m.image, -1) << m.name;
        EXPECT_TRUE(m.texcoords.empty()) << m.name;
        EXPECT_EQ(m.color, m.name == "gone" ? glm::vec3(0.2f, 0.4f, 0.6f) : glm::vec3(0.6f, 0.4f, 0.2f)) << m.name;
    }
}

// A .glb's picture is embedded in the file; the same model as .gltf names
// it as a file beside it. Both read with the look give the picture libpng
// decodes from that file (image/png.h), by another decoder than stb_image.
TEST(LoadScene, ModelPictureEmbeddedInAGlbIsTheFileBesideItsGltf)
{
    const std::string models = "/usr/share/assimp/models/glTF2/";
    const std::string glb = models + "BoxTextured-glTF-Binary/BoxTextured.glb",
                      gltf = models + "BoxTextured-glTF/BoxTextured.gltf",
                      png = models + "BoxTextured-glTF/CesiumLogoFlat.png";
    if (!std::filesystem::exists(glb) || !std::filesystem::exists(gltf) || !std::filesystem::exists(png))
        GTEST_SKIP() << "assimp-testmodels' BoxTextured is not installed (tools/deps.sh test installs it)";
    std::vector<std::string> warnings;
    const Scene embedded = load_scene(glb, &warnings, with_look()), beside = load_scene(gltf, &warnings, with_look());
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    int width = 0, height = 0;
    const std::vector<std::uint8_t> expected = read_png(png, width, height);
    for (const Scene *s : {&embedded, &beside}) {
        ASSERT_EQ(s->images.size(), 1u);
        EXPECT_EQ(s->images[0].width, width);
        EXPECT_EQ(s->images[0].height, height);
        EXPECT_EQ(s->images[0].rgba, expected);
        for (const Mesh &m : s->meshes) {
            EXPECT_EQ(m.image, 0);
            EXPECT_EQ(m.texcoords.size(), m.positions.size());
        }
    }
}
