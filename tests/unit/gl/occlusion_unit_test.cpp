// SPDX-License-Identifier: MIT
// The library's owner of GL_MESAX_occlusion_unit: a pass over a drawn
// rectangle returns named records with the analytic counts and extents,
// verbose lists exactly the pixels (flagging an overflow), and GL state
// and the framebuffer are as before the pass.
#include "gl/occlusion_unit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
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

// A conservative pass (GL_MESAX_occlusion_unit_conservative) answers each
// tile with nohc 1 or 0 and an empty record otherwise, on the extension or,
// where a context lacks it, on a brief pass: both say which tiles saw a
// passing fragment.
TEST(OcclusionUnit, ConservativeRecordsSayWhichTilesPassed)
{
    gl::OffscreenContext ctx(64, 64);
    const gl::OcclusionUnit unit;
    EXPECT_EQ(gl::OcclusionUnit::conservative_available(), gl::OcclusionUnit::available())
        << "occu's drivers advertise the conservative mode wherever they have the unit";
    pixel_exact_projection(64, 64);
    glEnable(GL_DEPTH_TEST);
    glClear(GL_DEPTH_BUFFER_BIT);
    rectangle(0, 0, 32, 64);   // window z 0.5 over the left half
    glDepthFunc(GL_LESS);
    gl::OcclusionPass pass(unit, gl::OcclusionMode::conservative, {{0, 0, 32, 64}, {32, 0, 64, 64}, {0, 0, 64, 64}});
    glBegin(GL_QUADS);   // behind (window z 0.75) over the window
    glVertex3f(0, 0, -0.5f);
    glVertex3f(64, 0, -0.5f);
    glVertex3f(64, 64, -0.5f);
    glVertex3f(0, 64, -0.5f);
    glEnd();
    const auto &r = pass.end();
    glDisable(GL_DEPTH_TEST);
    ASSERT_EQ(r.size(), 3u);
    const std::uint32_t expected_nohc[3] = {0, 1, 1};
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(r[i].nohc, expected_nohc[i]) << "tile " << i;
        EXPECT_EQ(r[i].phc, 0u) << "tile " << i;
        EXPECT_EQ(r[i].x_min, 0xFFFFFFFFu) << "tile " << i;
        EXPECT_EQ(r[i].x_max, 0u) << "tile " << i;
        EXPECT_TRUE(r[i].pixels.empty());
    }
    GLint mode = 0;
    glGetIntegerv(GL_RENDER_MODE, &mode);
    EXPECT_EQ(mode, GL_RENDER);
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

// --- asynchronous passes (GL_MESAX_occlusion_unit_async, issue 14) -----------

namespace {

// A 32 x 16 frame whose left half holds a near rectangle (window z 0.5);
// a pass draws a far quad (window z 0.75) over all of it, so the left tile
// (0..16) is occluded and the right one (16..32) sees 256 fragments.
void near_rectangle_on_the_left()
{
    pixel_exact_projection(32, 16);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glColor3f(0, 0, 1);
    rectangle(0, 0, 16, 16);
}

void far_quad()
{
    glBegin(GL_QUADS);
    glVertex3f(0, 0, -0.5f);
    glVertex3f(32, 0, -0.5f);
    glVertex3f(32, 16, -0.5f);
    glVertex3f(0, 16, -0.5f);
    glEnd();
}

const std::vector<PixelRect> left_and_right = {{0, 0, 16, 16}, {16, 0, 32, 16}};

// What every backend must do: records as the synchronous pass's, RENDER_MODE
// back to GL_RENDER at end(), nothing drawn by the pass, and conditional
// rendering on a tile drawing only behind a tile that saw fragments.
void check_async_backend(gl::OffscreenContext &ctx, const gl::OcclusionUnit &unit)
{
    near_rectangle_on_the_left();
    std::vector<gl::OcclusionRecord> sync;
    {
        gl::OcclusionPass pass(unit, gl::OcclusionMode::brief, left_and_right);
        far_quad();
        sync = pass.end();
    }
    glFinish();
    const std::vector<std::uint8_t> before(ctx.pixels(), ctx.pixels() + 32 * 16 * 4);

    gl::AsyncOcclusionPass pass(unit);
    EXPECT_EQ(pass.native(), unit.native_async());
    EXPECT_FALSE(pass.available()) << "no records before a pass";
    for (int round = 0; round < 2; ++round) {   // a pass object serves pass after pass
        pass.begin(gl::OcclusionMode::brief, left_and_right);
        GLint mode = 0;
        glGetIntegerv(GL_RENDER_MODE, &mode);
        EXPECT_EQ(mode, GL_BRIEF_OCCLUSION_MESAX);
        far_quad();
        pass.end();
        glGetIntegerv(GL_RENDER_MODE, &mode);
        EXPECT_EQ(mode, GL_RENDER);
        const auto &records = pass.records();
        EXPECT_TRUE(pass.available()) << "records read, yet not available";
        ASSERT_EQ(records.size(), 2u);
        for (std::size_t i = 0; i < 2; ++i) {
            EXPECT_EQ(records[i].nohc, sync[i].nohc) << "tile " << i;
            EXPECT_EQ(records[i].phc, sync[i].phc) << "tile " << i;
            EXPECT_EQ(records[i].x_min, sync[i].x_min) << "tile " << i;
            EXPECT_EQ(records[i].z_max, sync[i].z_max) << "tile " << i;
        }
        EXPECT_EQ(records[0].nohc, 0u);
        EXPECT_EQ(records[1].nohc, 256u);
    }
    glFinish();
    EXPECT_TRUE(std::equal(before.begin(), before.end(), ctx.pixels())) << "a pass drew into the framebuffer";

    // Conditional rendering: a red rectangle in front of everything, drawn
    // under tile 0 (occluded: skipped) and tile 1 (seen: drawn).
    glColor3f(1, 0, 0);
    glDepthFunc(GL_ALWAYS);
    for (std::size_t tile = 0; tile < 2; ++tile) {
        const gl::ConditionalTileRender c(pass, tile, 0, 0.0f, true);
        if (c.draws())
            rectangle(int(tile) * 16, 0, int(tile) * 16 + 16, 16);
    }
    // A ratio the right tile does not reach (NOHC = PHC): nothing drawn.
    glColor3f(0, 1, 0);
    {
        const gl::ConditionalTileRender c(pass, 1, 0, 1.0f, false);
        if (c.draws())
            rectangle(16, 0, 32, 16);
    }
    glDepthFunc(GL_LESS);
    glFinish();
    const std::uint8_t *left = ctx.pixels() + (8 * 32 + 8) * 4, *right = ctx.pixels() + (8 * 32 + 24) * 4;
    EXPECT_EQ(left[0], 0) << "drawn under an occluded tile";
    EXPECT_EQ(left[2], 255) << "the near rectangle is gone";
    EXPECT_EQ(right[0], 255) << "not drawn under a tile that saw fragments";
    EXPECT_EQ(right[1], 0) << "drawn although NOHC is not above 1.0 * PHC";
    glDisable(GL_DEPTH_TEST);
}

}  // namespace

// The emulation on the synchronous RenderMode path, which the library uses
// where the context lacks the extension: always tested, whatever the driver has.
TEST(AsyncOcclusionPass, EmulationOnRenderModeBehavesAsTheExtension)
{
    gl::OffscreenContext ctx(32, 16);
    const gl::OcclusionUnit unit(false);
    ASSERT_FALSE(unit.native_async());
    check_async_backend(ctx, unit);
    gl::AsyncOcclusionPass pass(unit);
    pass.begin(gl::OcclusionMode::brief, {});
    pass.end();
    EXPECT_TRUE(pass.available()) << "an emulated pass is read at its end";
    EXPECT_EQ(pass.name(), 0u);
}

// The backend a unit chooses for this context: the extension's entry points
// when the context advertises GL_MESAX_occlusion_unit_async, else the
// emulation. Never skipped: it says which path ran (test output and the
// "async_backend" property in the XML report).
TEST(AsyncOcclusionPass, ChosenBackendForThisContext)
{
    gl::OffscreenContext ctx(32, 16);
    const gl::OcclusionUnit unit;
    const bool advertised = gl::OcclusionUnit::async_available();
    EXPECT_EQ(unit.native_async(), advertised);
    const char *backend = unit.native_async() ? "native GL_MESAX_occlusion_unit_async"
                                              : "emulated on glRenderMode (the context lacks GL_MESAX_occlusion_unit_async)";
    std::printf("asynchronous occlusion passes: %s\n", backend);
    ::testing::Test::RecordProperty("async_backend", unit.native_async() ? "native" : "emulated");
    check_async_backend(ctx, unit);
    if (!unit.native_async())
        return;
    // The extension's own promises: a pass has a name, it is a pass
    // object, and its records become available without a Get of RESULT.
    gl::AsyncOcclusionPass pass(unit);
    EXPECT_NE(pass.name(), 0u);
    auto is_pass = reinterpret_cast<PFNGLISOCCLUSIONPASSMESAXPROC>(gl::get_proc_address("glIsOcclusionPassMESAX"));
    ASSERT_NE(is_pass, nullptr);
    pass.begin(gl::OcclusionMode::brief, left_and_right);
    far_quad();
    pass.end();
    EXPECT_TRUE(is_pass(pass.name()));
    glFinish();   // the pass's scene is done after a finish
    EXPECT_TRUE(pass.available()) << "records not available after glFinish";
}
