// SPDX-License-Identifier: MIT
// Strategies never touch the caller's framebuffer or GL state: each one's
// begin_frame and tests leave the colour and depth buffers, the viewport,
// the matrices and the enables exactly as the caller set them (their
// occluder images go to framebuffers of their own).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "camera/route.h"
#include "culling/databases.h"
#include "culling/registry.h"
#include "evaluation/oracle.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "scene/city.h"

#include "small_city.h"

using namespace occu;

TEST(Cullers, LeaveTheCallersFramebufferAndStateAlone)
{
    const integration::SmallCity city(3, 256, 96);
    const gl::OffscreenContext &ctx = city.ctx;
    const Hierarchy &h = city.h;
    const StrategyContext context = city.context();
    const Camera camera = city.setup.route("dense", 1)[0];
    Oracle oracle(city.renderer, h);
    const VisibilityTruth truth = oracle.see(camera, 96, 96);
    const Frame frame(camera, 96, 96, &truth);

    // The databases strategies require, made on demand, small (one view per heading).
    DatabaseProvider databases(::testing::TempDir() + "occu-culler-framebuffer-" + std::to_string(getpid()),
                               DatabaseProvider::Makes::required, nullptr);
    const std::vector<std::string> small = {"database-grid=1", "database-headings=4"};
    for (const std::string &name : strategy_names()) {
        SCOPED_TRACE(name);
        // A family that cannot serve the city (bsp-pvs: no BSP) is never made on it.
        if (!choose_strategy(name).family->refusal(city.setup.scene()).empty())
            continue;
        std::vector<std::string> settings = small;
        for (const std::string &d : databases.settings_for(choose_strategy(name, small), context, 96, 96))
            settings.push_back(d);
        const Strategy s = make_strategy(name, context, settings);
        // A caller's frame in progress: a gradient of colour and depth.
        glEnable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glDepthFunc(GL_ALWAYS);
        glClearColor(0.2f, 0.3f, 0.4f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glMatrixMode(GL_PROJECTION);
        glLoadIdentity();
        glMatrixMode(GL_MODELVIEW);
        glLoadIdentity();
        glBegin(GL_TRIANGLES);
        glColor3f(1, 0, 0);
        glVertex3f(-1, -1, -0.5f);
        glColor3f(0, 1, 0);
        glVertex3f(1, -1, 0.0f);
        glColor3f(0, 0, 1);
        glVertex3f(0, 1, 0.7f);
        glEnd();
        glFinish();
        std::vector<float> depth_before(96 * 96), depth_after(96 * 96);
        glReadPixels(0, 0, 96, 96, GL_DEPTH_COMPONENT, GL_FLOAT, depth_before.data());
        const std::vector<std::uint8_t> colour_before(ctx.pixels(), ctx.pixels() + 96 * 96 * 4);
        GLfloat projection_before[16], projection_after[16];
        glGetFloatv(GL_PROJECTION_MATRIX, projection_before);

        s.culler->begin_frame(frame);
        std::vector<NodeTest> tests;
        for (std::uint32_t n = 0; n < h.nodes().size() && tests.size() < 40; ++n)
            tests.push_back({n, h.nodes()[n].bounds, h.nodes()[n].leaf()});
        s.culler->test(tests);
        glFinish();

        glReadPixels(0, 0, 96, 96, GL_DEPTH_COMPONENT, GL_FLOAT, depth_after.data());
        EXPECT_TRUE(depth_before == depth_after) << "depth buffer changed";
        EXPECT_TRUE(std::equal(colour_before.begin(), colour_before.end(), ctx.pixels())) << "colour buffer changed";
        glGetFloatv(GL_PROJECTION_MATRIX, projection_after);
        EXPECT_TRUE(std::equal(projection_before, projection_before + 16, projection_after)) << "projection changed";
        GLint viewport[4], depth_func = 0;
        glGetIntegerv(GL_VIEWPORT, viewport);
        glGetIntegerv(GL_DEPTH_FUNC, &depth_func);
        EXPECT_EQ(viewport[2], 96);
        EXPECT_EQ(viewport[3], 96);
        EXPECT_EQ(depth_func, GL_ALWAYS);
        EXPECT_FALSE(glIsEnabled(GL_CULL_FACE));
        EXPECT_TRUE(glIsEnabled(GL_DEPTH_TEST));
        GLint fbo = -1;
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
        EXPECT_EQ(fbo, 0);
    }
    std::filesystem::remove_all(databases.directory());
}
