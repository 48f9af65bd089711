/* SPDX-License-Identifier: MIT */
/*
 * A fragment shader's depth outside [0, 1] is clamped to [0, 1] before the
 * depth test and the depth write (OpenGL 4.6, section 15.2.3: gl_FragDepth
 * is clamped to [0, 1] and converted as a window z; depth values outside
 * [0, 1] are allowed only by NV_depth_buffer_float, which Mesa does not
 * expose), for every primitive and depth format, fixed-point or float.
 *
 * A 64 x 64 framebuffer, the depth test on, depth range [0, 1], a shader
 * writing a constant depth and white:
 *   - gl_FragDepth = -0.5 over depth cleared to 0.25, test LESS: every
 *     fragment passes and stores 0;
 *   - gl_FragDepth = 1.5 over depth cleared to 0.75, test GREATER: every
 *     fragment passes and stores 1.
 * "Passes" is checked as in GL_RENDER: the pixels written with the test
 * equal those written with it off, and are at least one; "stores" by
 * glReadPixels of the depth of every written pixel, within 2^-20 (a 24-bit
 * value read back as a float is within 2^-24 of the stored one).
 * Each with a triangle, a line of width 1 and a point of size 1.
 *
 * Subtests: d24s8-below-zero, d24s8-above-one (the window-system buffer),
 * d32f-below-zero, d32f-above-one (a framebuffer object with a
 * DEPTH_COMPONENT32F renderbuffer; ARB_depth_buffer_float).
 */
#include <math.h>
#include <stdio.h>

#include "piglit-util-gl.h"

enum { S = 64 };

static PFNGLUSEPROGRAMPROC UseProgram;

static void
primitives(void)
{
    glBegin(GL_TRIANGLES);
    glVertex2f(4, 4);
    glVertex2f(40, 6);
    glVertex2f(20, 30);
    glEnd();
    glBegin(GL_LINES);
    glVertex2f(4.3f, 40.2f);
    glVertex2f(60.1f, 50.7f);
    glEnd();
    glBegin(GL_POINTS);
    glVertex2f(50.5f, 10.5f);
    glEnd();
}

static unsigned
drawn(GLenum func, double clear, GLubyte pixels[S][S][4], float depths[S][S])
{
    unsigned n = 0;
    glClearDepth(clear);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDepthFunc(func);
    primitives();
    glReadPixels(0, 0, S, S, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    glReadPixels(0, 0, S, S, GL_DEPTH_COMPONENT, GL_FLOAT, depths);
    for (int y = 0; y < S; ++y)
        for (int x = 0; x < S; ++x)
            n += pixels[y][x][0] != 0;
    return n;
}

static bool
check(const char *name, const char *depth, GLenum func, double clear, float stored)
{
    static GLubyte pixels[S][S][4];
    static float depths[S][S];
    char source[160];
    snprintf(source, sizeof(source),
             "#version 110\nvoid main() { gl_FragDepth = %s; gl_FragColor = vec4(1.0); }\n", depth);
    const GLuint program = piglit_build_simple_program(NULL, source);
    if (!program) {
        printf("%s: the shader did not build\n", name);
        return false;
    }
    UseProgram(program);
    const unsigned all = drawn(GL_ALWAYS, clear, pixels, depths);
    const unsigned passing = drawn(func, clear, pixels, depths);
    unsigned wrong = 0;
    for (int y = 0; y < S; ++y) {
        for (int x = 0; x < S; ++x) {
            if (pixels[y][x][0] && !(fabsf(depths[y][x] - stored) <= 1.0f / (1 << 20))) {
                if (wrong++ == 0)
                    printf("%s: pixel (%d, %d) stores depth %.9g, expected %g\n", name, x, y, depths[y][x], stored);
            }
        }
    }
    UseProgram(0);
    const bool ok = all > 0 && passing == all && wrong == 0 && piglit_check_gl_error(GL_NO_ERROR);
    if (passing != all || all == 0)
        printf("%s: %u pixels pass, %u drawn with the test off\n", name, passing, all);
    piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "%s", name);
    return ok;
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 20;
    config.window_width = S;
    config.window_height = S;
    config.window_visual = PIGLIT_GL_VISUAL_RGBA | PIGLIT_GL_VISUAL_DEPTH | PIGLIT_GL_VISUAL_STENCIL;
    config.khr_no_error_support = PIGLIT_NO_ERRORS;

PIGLIT_GL_TEST_CONFIG_END

enum piglit_result
piglit_display(void)
{
    /* piglit_init reports the result. */
    return PIGLIT_FAIL;
}

void
piglit_init(int argc, char **argv)
{
    bool ok = true;

    UseProgram = glUseProgram;
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, S, 0, S, -1, 1);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glClearColor(0, 0, 0, 0);
    glEnable(GL_DEPTH_TEST);

    ok = check("d24s8-below-zero", "-0.5", GL_LESS, 0.25, 0.0f) && ok;
    ok = check("d24s8-above-one", "1.5", GL_GREATER, 0.75, 1.0f) && ok;

    if (!piglit_is_extension_supported("GL_ARB_depth_buffer_float")) {
        /* softpipe and llvmpipe both expose it. */
        printf("GL_ARB_depth_buffer_float is not supported\n");
        piglit_report_subtest_result(PIGLIT_FAIL, "d32f-below-zero");
        piglit_report_subtest_result(PIGLIT_FAIL, "d32f-above-one");
        piglit_report_result(PIGLIT_FAIL);
    }
    PFNGLGENFRAMEBUFFERSPROC GenFramebuffers =
        glGenFramebuffers;
    PFNGLBINDFRAMEBUFFERPROC BindFramebuffer =
        glBindFramebuffer;
    PFNGLGENRENDERBUFFERSPROC GenRenderbuffers =
        glGenRenderbuffers;
    PFNGLBINDRENDERBUFFERPROC BindRenderbuffer =
        glBindRenderbuffer;
    PFNGLRENDERBUFFERSTORAGEPROC RenderbufferStorage =
        glRenderbufferStorage;
    PFNGLFRAMEBUFFERRENDERBUFFERPROC FramebufferRenderbuffer =
        glFramebufferRenderbuffer;
    PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus =
        glCheckFramebufferStatus;
    GLuint fbo, rb[2];
    GenFramebuffers(1, &fbo);
    BindFramebuffer(GL_FRAMEBUFFER, fbo);
    GenRenderbuffers(2, rb);
    BindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, S, S);
    FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    BindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, S, S);
    FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    if (CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        printf("the DEPTH_COMPONENT32F framebuffer is not complete\n");
        piglit_report_subtest_result(PIGLIT_FAIL, "d32f-below-zero");
        piglit_report_subtest_result(PIGLIT_FAIL, "d32f-above-one");
        piglit_report_result(PIGLIT_FAIL);
    }
    ok = check("d32f-below-zero", "-0.5", GL_LESS, 0.25, 0.0f) && ok;
    ok = check("d32f-above-one", "1.5", GL_GREATER, 0.75, 1.0f) && ok;
    piglit_report_result(ok ? PIGLIT_PASS : PIGLIT_FAIL);
}
