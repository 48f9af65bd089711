// SPDX-License-Identifier: MIT
// The HP test's flag: the cheapest boolean occlusion query a context
// offers, and that query, in the current context, answering a box behind
// an occluder and one beside it.
#include "gl/occlusion_query.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "gl/offscreen_context.h"

using namespace occu;
using occu::gl::boolean_occlusion_query_target;

TEST(BooleanOcclusionQueryTarget, TheConservativeFlagFromGl43OrEs3Compatibility)
{
    EXPECT_EQ(boolean_occlusion_query_target(4, 3, {}), GLenum(GL_ANY_SAMPLES_PASSED_CONSERVATIVE));
    EXPECT_EQ(boolean_occlusion_query_target(4, 5, {}), GLenum(GL_ANY_SAMPLES_PASSED_CONSERVATIVE));
    EXPECT_EQ(boolean_occlusion_query_target(3, 3, {"GL_ARB_ES3_compatibility"}),
              GLenum(GL_ANY_SAMPLES_PASSED_CONSERVATIVE));
}

TEST(BooleanOcclusionQueryTarget, TheExactFlagFromGl33OrOcclusionQuery2)
{
    EXPECT_EQ(boolean_occlusion_query_target(3, 3, {"GL_ARB_occlusion_query"}), GLenum(GL_ANY_SAMPLES_PASSED));
    EXPECT_EQ(boolean_occlusion_query_target(4, 2, {}), GLenum(GL_ANY_SAMPLES_PASSED));
    EXPECT_EQ(boolean_occlusion_query_target(2, 1, {"GL_ARB_occlusion_query2"}), GLenum(GL_ANY_SAMPLES_PASSED));
}

TEST(BooleanOcclusionQueryTarget, TheCountBelow)
{
    EXPECT_EQ(boolean_occlusion_query_target(3, 2, {"GL_ARB_occlusion_query"}), GLenum(GL_SAMPLES_PASSED));
    EXPECT_EQ(boolean_occlusion_query_target(1, 5, {}), GLenum(GL_SAMPLES_PASSED));
    // A name that merely begins like one does not count.
    EXPECT_EQ(boolean_occlusion_query_target(2, 1, {"GL_ARB_occlusion_query2_x"}), GLenum(GL_SAMPLES_PASSED));
}

// In the current context: no GL error, a quad behind a nearer one answers
// 0 and a quad beside it not 0. These drivers answer the conservative flag
// exactly (the hp strategy culls a box only on 0, so a driver that answered
// true there would only cull less).
TEST(BooleanOcclusionQueryTarget, TheCurrentContextsQueryAnswersHiddenAndVisible)
{
    gl::OffscreenContext ctx(64, 64);
    const GLenum target = boolean_occlusion_query_target();
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major > 4 || (major == 4 && minor >= 3))
        EXPECT_EQ(target, GLenum(GL_ANY_SAMPLES_PASSED_CONSERVATIVE));
    std::printf("GL %d.%d: query target 0x%04X\n", major, minor, target);

    const auto gl_query = gl::QueryFunctions::load("this test");

    glViewport(0, 0, 64, 64);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, 64, 0, 64, -1, 1);   // depth = (1 - z) / 2: larger z nearer
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    auto quad = [](float x0, float y0, float x1, float y1, float z) {
        glBegin(GL_QUADS);
        glVertex3f(x0, y0, z);
        glVertex3f(x1, y0, z);
        glVertex3f(x1, y1, z);
        glVertex3f(x0, y1, z);
        glEnd();
    };
    quad(0, 0, 32, 64, 0.5f);   // the occluder: the left half, near

    GLuint queries[2];
    gl_query.GenQueries(2, queries);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    gl_query.BeginQuery(target, queries[0]);
    quad(4, 4, 28, 60, -0.5f);   // behind the occluder
    gl_query.EndQuery(target);
    gl_query.BeginQuery(target, queries[1]);
    quad(36, 4, 60, 60, -0.5f);   // beside it, in front of the cleared depth
    gl_query.EndQuery(target);
    GLuint hidden = 7, visible = 0;
    gl_query.GetQueryObjectuiv(queries[0], GL_QUERY_RESULT, &hidden);
    gl_query.GetQueryObjectuiv(queries[1], GL_QUERY_RESULT, &visible);
    gl_query.DeleteQueries(2, queries);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    EXPECT_EQ(hidden, 0u);
    EXPECT_NE(visible, 0u);
}
