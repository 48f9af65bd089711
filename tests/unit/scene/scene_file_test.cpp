#include "scene/scene_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

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
