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
