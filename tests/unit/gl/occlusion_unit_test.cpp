// The library's owner of GL_MESAX_occlusion_unit: a pass over a drawn
// rectangle returns named records with the analytic counts and extents,
// verbose lists exactly the pixels (flagging an overflow), and GL state
// and the framebuffer are as before the pass.
#include "gl/occlusion_unit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>

#include "gl/offscreen_context.h"

using namespace occu;

namespace {

// Window coordinates as object coordinates: a rectangle from (x0, y0) to
// (x1, y1) covers the pixels x0..x1-1, y0..y1-1.
void pixel_exact_projection(int w, int h)
{
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, w, 0, h, -1, 1);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
}

void rectangle(int x0, int y0, int x1, int y1)
{
    glRecti(x0, y0, x1, y1);
}

}  // namespace

TEST(OcclusionUnit, BriefRecordsAreNamedAndExact)
{
    gl::OffscreenContext ctx(64, 64);
    const gl::OcclusionUnit unit;
    EXPECT_GE(unit.max_tiles(), 64);
    pixel_exact_projection(64, 64);
    glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glFinish();
    const std::vector<std::uint8_t> before(ctx.pixels(), ctx.pixels() + 64 * 64 * 4);
    gl::OcclusionPass pass(unit, gl::OcclusionMode::brief, {{0, 0, 32, 64}, {32, 0, 64, 64}});
    rectangle(10, 20, 40, 30);   // 22 x 10 pixels in tile 0, 8 x 10 in tile 1
    const auto &records = pass.end();
    ASSERT_EQ(records.size(), 2u);
    EXPECT_EQ(records[0].nohc, 220u);
    EXPECT_EQ(records[0].phc, 220u);
    EXPECT_EQ(records[1].nohc, 80u);
    EXPECT_EQ(records[0].x_min, 10u);
    EXPECT_EQ(records[0].x_max, 31u);
    EXPECT_EQ(records[1].x_min, 32u);
    EXPECT_EQ(records[1].x_max, 39u);
    EXPECT_EQ(records[0].y_min, 20u);
    EXPECT_EQ(records[0].y_max, 29u);
    EXPECT_TRUE(records[0].pixels.empty());
    GLint mode = 0;
    glGetIntegerv(GL_RENDER_MODE, &mode);
    EXPECT_EQ(mode, GL_RENDER);
    glFinish();
    EXPECT_TRUE(std::equal(before.begin(), before.end(), ctx.pixels())) << "a pass drew into the framebuffer";
}

TEST(OcclusionUnit, VerboseListsThePixelsAndFlagsAnOverflow)
{
    gl::OffscreenContext ctx(32, 32);
    const gl::OcclusionUnit unit;
    pixel_exact_projection(32, 32);
    gl::OcclusionPass pass(unit, gl::OcclusionMode::verbose, {{0, 0, 16, 32}, {16, 0, 32, 32}}, {100, 5});
    rectangle(4, 4, 24, 8);   // 12 x 4 = 48 pixels in tile 0, 8 x 4 = 32 in tile 1
    const auto &records = pass.end();
    std::set<std::pair<std::uint32_t, std::uint32_t>> listed, expected;
    for (const auto &p : records[0].pixels)
        listed.insert({p.x, p.y});
    for (std::uint32_t y = 4; y < 8; ++y)
        for (std::uint32_t x = 4; x < 16; ++x)
            expected.insert({x, y});
    EXPECT_FALSE(records[0].overflowed);
    EXPECT_EQ(records[0].pixels.size(), 48u);
    EXPECT_EQ(listed, expected);
    EXPECT_TRUE(records[1].overflowed);
    EXPECT_EQ(records[1].nohc, 32u);
    EXPECT_EQ(records[1].pixels.size(), 5u);
    for (const auto &p : records[1].pixels)
        EXPECT_TRUE(p.x >= 16 && p.x < 24 && p.y >= 4 && p.y < 8) << p.x << "," << p.y;
}

TEST(OcclusionUnit, DepthTestedFragmentsOnlyPassWhereInFront)
{
    gl::OffscreenContext ctx(16, 16);
    const gl::OcclusionUnit unit;
    pixel_exact_projection(16, 16);
    glEnable(GL_DEPTH_TEST);
    glClear(GL_DEPTH_BUFFER_BIT);
    rectangle(0, 0, 8, 16);   // z = 0 (window 0.5) over the left half
    glDepthFunc(GL_LESS);
    gl::OcclusionPass pass(unit, gl::OcclusionMode::brief, {});
    glBegin(GL_QUADS);   // behind (window z 0.75) over all 16 x 16
    glVertex3f(0, 0, -0.5f);
    glVertex3f(16, 0, -0.5f);
    glVertex3f(16, 16, -0.5f);
    glVertex3f(0, 16, -0.5f);
    glEnd();
    const auto &r = pass.end();
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].phc, 256u);
    EXPECT_EQ(r[0].nohc, 128u);
    EXPECT_EQ(r[0].x_min, 8u);
    glDisable(GL_DEPTH_TEST);
}

TEST(OcclusionUnit, MoreTilesThanTheUnitHasAreRefused)
{
    gl::OffscreenContext ctx(8, 8);
    const gl::OcclusionUnit unit;
    std::vector<PixelRect> tiles(std::size_t(unit.max_tiles()) + 1, PixelRect{0, 0, 1, 1});
    EXPECT_THROW(gl::OcclusionPass(unit, gl::OcclusionMode::brief, tiles), std::invalid_argument);
    GLint mode = 0;
    glGetIntegerv(GL_RENDER_MODE, &mode);
    EXPECT_EQ(mode, GL_RENDER);
}
