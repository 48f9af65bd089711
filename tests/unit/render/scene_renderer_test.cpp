// SPDX-License-Identifier: MIT
// SceneRenderer's looks: Look::scene draws a mesh's picture times its vertex
// light or its lightmap, a model's picture the right way up; draw_leaf_flat
// never textures, whatever the look.
#include "render/scene_renderer.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gl/offscreen_context.h"
#include "image/png.h"
#include "render/shading.h"
#include "scene/scene_file.h"
#include "spatial/hierarchy.h"

using namespace occu;

namespace {

constexpr int view = 16;

// A quad over the whole viewport (clip coordinates under identity
// matrices), its picture one colour; lightmapped under a grey atlas, or
// lit by its vertices.
Scene quad_scene(bool lightmapped)
{
    Scene s;
    Mesh m;
    m.name = "quad";
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    m.normals.assign(4, {0, 0, 1});
    m.indices = {0, 1, 2, 0, 2, 3};
    m.color = {0.1f, 0.9f, 0.1f};
    m.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.vertex_light.assign(4, 0xff80ffffu);   // R 255, G 255, B 128 (the low byte is red)
    m.image = 0;
    Image picture;
    picture.width = picture.height = 2;
    for (int i = 0; i < 4; ++i)
        picture.rgba.insert(picture.rgba.end(), {200, 100, 50, 255});
    s.images.push_back(picture);
    if (lightmapped) {
        m.lightmapped = true;
        m.lightmap_coords.assign(4, {0.5f, 0.5f});
        Image atlas;
        atlas.width = atlas.height = 1;
        atlas.rgba = {128, 128, 128, 255};
        s.lightmap_atlas = 1;
        s.images.push_back(atlas);
    }
    s.meshes.push_back(m);
    s.update_bounds();
    return s;
}

// The centre pixel after drawing every leaf with `draw`.
template <class Draw>
std::array<int, 3> centre(gl::OffscreenContext &ctx, const Hierarchy &h, Draw draw)
{
    glViewport(0, 0, view, view);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    for (std::uint32_t n = 0; n < h.nodes().size(); ++n)
        if (h.nodes()[n].leaf())
            draw(n);
    glFinish();
    const std::uint8_t *p = ctx.pixels() + 4 * (view / 2 * view + view / 2);
    return {p[0], p[1], p[2]};
}

}  // namespace

TEST(SceneRenderer, SceneLookIsThePictureTimesItsLight)
{
    gl::OffscreenContext ctx(view, view);
    for (bool lightmapped : {false, true}) {
        const Scene s = quad_scene(lightmapped);
        const Hierarchy h = Hierarchy::build(s);
        const SceneRenderer look(s, h, Look::scene), flat(s, h, Look::flat);
        EXPECT_TRUE(look.textured());
        EXPECT_FALSE(flat.textured());
        const std::array<int, 3> c = centre(ctx, h, [&](std::uint32_t n) { look.draw_leaf(n); });
        // Vertex light (255, 255, 128), or the grey lightmap (128).
        const std::array<int, 3> want = lightmapped ? std::array<int, 3>{100, 50, 25} : std::array<int, 3>{200, 100, 25};
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(c[k], want[k], 2) << "channel " << k << (lightmapped ? ", lightmapped" : ", vertex light");
        // The flat look: the mesh's own green, pre-lit.
        const std::array<int, 3> f = centre(ctx, h, [&](std::uint32_t n) { flat.draw_leaf(n); });
        EXPECT_GT(f[1], 150);
        EXPECT_LT(f[0], 60);
        // A pass that draws occluders or IDs: the caller's colour, no texture left bound.
        const std::array<int, 3> id = centre(ctx, h, [&](std::uint32_t n) {
            glColor3ub(0, 255, 0);
            look.draw_leaf_flat(n);
        });
        EXPECT_EQ(id, (std::array<int, 3>{0, 255, 0}));
        EXPECT_FALSE(glIsEnabled(GL_TEXTURE_2D)) << "the look leaves no texturing on";
    }
}

// A model read with its look (scene/scene_file.h) is drawn with its
// material's picture the right way up: each quadrant of the frame shows
// the same quadrant of the picture, times the material's colour pre-lit.
TEST(SceneRenderer, ModelPictureIsDrawnUprightTimesItsMaterialColour)
{
    const std::string dir = ::testing::TempDir() + "occu_" + std::to_string(getpid()) + "_model_look";
    std::filesystem::create_directories(dir);
    // 4x4 texels, each quadrant 2x2 of one colour (top row first), so that
    // bilinear filtering inside a quadrant's middle gives its colour exactly.
    const std::uint8_t colours[4][4] = {{220, 30, 30, 255}, {30, 200, 40, 255}, {40, 50, 210, 255}, {230, 220, 60, 255}};
    std::vector<std::uint8_t> rgba;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            rgba.insert(rgba.end(), colours[(y >= 2 ? 2 : 0) + (x >= 2 ? 1 : 0)], colours[(y >= 2 ? 2 : 0) + (x >= 2 ? 1 : 0)] + 4);
    write_png(dir + "/q.png", 4, 4, rgba.data(), false);
    {
        std::ofstream(dir + "/q.mtl") << "newmtl m\nKd 0.9 0.8 0.7\nmap_Kd q.png\n";
        // The viewport's square in clip coordinates, texture coordinates
        // from its bottom-left (0, 0) to its top-right (1, 1) as OBJ files have them.
        std::ofstream(dir + "/q.obj") << "mtllib q.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                                         "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3 4/4\n";
    }
    Quake3Options look;
    look.look = true;
    const Scene s = load_scene(dir + "/q.obj", nullptr, look);
    std::filesystem::remove_all(dir);
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.meshes[0].image, 0);

    gl::OffscreenContext ctx(view, view);
    const Hierarchy h = Hierarchy::build(s);
    const SceneRenderer renderer(s, h, Look::scene);
    ASSERT_TRUE(renderer.textured());
    centre(ctx, h, [&](std::uint32_t n) { renderer.draw_leaf(n); });
    std::uint8_t light[4];
    prelit_rgba8(s.meshes[0].color, s.meshes[0].normals[0], light);
    // Pixel rows are bottom first: the picture's top-left quadrant is the
    // frame's upper left, at row 3/4 of the height.
    const int at[4][2] = {{view / 4, 3 * view / 4}, {3 * view / 4, 3 * view / 4}, {view / 4, view / 4}, {3 * view / 4, view / 4}};
    for (int q = 0; q < 4; ++q) {
        const std::uint8_t *p = ctx.pixels() + 4 * (at[q][1] * view + at[q][0]);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(p[k], colours[q][k] * light[k] / 255.0, 2) << "quadrant " << q << ", channel " << k;
    }
}
