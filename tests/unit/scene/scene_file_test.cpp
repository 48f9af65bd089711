#include "scene/scene_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

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
