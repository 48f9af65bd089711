/* SPDX-License-Identifier: MIT */
/*
 * With layout(early_fragment_tests) the alpha test still follows the
 * fragment shader and reads the alpha the shader wrote, while
 * GL_SAMPLES_PASSED counts at the early tests, before the shader, so the
 * fragments the alpha test removes are counted (ARB_shader_image_load_store;
 * OpenGL 4.6, section 14.9, Early Per-Fragment Tests: the early tests are
 * the stencil, depth buffer and depth bounds tests and the occlusion query's
 * counting; the alpha test, a per-fragment operation of the compatibility
 * profile, is not one of them and tests the alpha the shader wrote).
 *
 * A 64 x 64 framebuffer, depth cleared to 1, an occluder written to depth
 * alone at z 0.25 over columns 0..23; then, the depth test LESS and depth
 * writes off, a framebuffer-sized rectangle at z 0.5 inside a
 * GL_SAMPLES_PASSED query, with a shader with early fragment tests writing
 * white with alpha 1 on even rows and alpha 0 on odd rows, and the alpha
 * test GREATER 0.5.
 *
 * The expectations are computed from the same geometry and the shader's
 * formula: a pixel passes the depth test where its centre is outside the
 * occluder, and the alpha test where its row is even. Tolerance 0: a
 * single-sampled buffer counts whole pixels, every edge lies on pixel
 * boundaries (no pixel centre on an edge), and the alphas 0 and 1 are exact
 * in every colour format and far from the reference 0.5.
 *
 * Subtests:
 *   samples-passed-counts-alpha-tested-fragments  GL_SAMPLES_PASSED is the
 *       number of pixels passing the depth test, those the alpha test
 *       removes included
 *   alpha-test-follows-shader  the pixels written are exactly those passing
 *       the depth test whose shader alpha passes the alpha test
 */
#include <stdio.h>

#include "piglit-util-gl.h"

enum { S = 64, OCCLUDER_RIGHT = 24 };

static const char fragment_source[] =
    "#version 150 compatibility\n"
    "#extension GL_ARB_shader_image_load_store : require\n"
    "layout(early_fragment_tests) in;\n"
    "void main() {\n"
    "  float alpha = mod(floor(gl_FragCoord.y), 2.0) == 0.0 ? 1.0 : 0.0;\n"
    "  gl_FragColor = vec4(1.0, 1.0, 1.0, alpha);\n"
    "}\n";

/* The shader's alpha for a pixel's row, as the shader computes it. */
static float
shader_alpha(int y)
{
    return y % 2 == 0 ? 1.0f : 0.0f;
}

static bool
passes_depth_test(int x)
{
    /* The pixel's centre against the occluder's right edge. */
    return x + 0.5f > OCCLUDER_RIGHT;
}

static void
rect(float x0, float y0, float x1, float y1, float z)
{
    glBegin(GL_QUADS);
    glVertex3f(x0, y0, z);
    glVertex3f(x1, y0, z);
    glVertex3f(x1, y1, z);
    glVertex3f(x0, y1, z);
    glEnd();
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 32;
    config.window_width = S;
    config.window_height = S;
    config.window_visual = PIGLIT_GL_VISUAL_RGBA | PIGLIT_GL_VISUAL_DEPTH;
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
    static GLubyte pixels[S][S][4];
    unsigned depth_passing = 0, alpha_removed = 0, wrong = 0;
    GLuint query, samples = 0xdeadbeefu;

    /* layout(early_fragment_tests) is ARB_shader_image_load_store's. */
    piglit_require_extension("GL_ARB_shader_image_load_store");
    const GLuint program = piglit_build_simple_program(NULL, fragment_source);

    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, S, 0, S, 0, -1);   /* object z is window z */
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    rect(0, 0, OCCLUDER_RIGHT, S, 0.25f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_FALSE);

    glUseProgram(program);
    glEnable(GL_ALPHA_TEST);
    glAlphaFunc(GL_GREATER, 0.5f);
    glGenQueries(1, &query);
    glBeginQuery(GL_SAMPLES_PASSED, query);
    rect(0, 0, S, S, 0.5f);
    glEndQuery(GL_SAMPLES_PASSED);
    glDisable(GL_ALPHA_TEST);
    glUseProgram(0);
    glGetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    glReadPixels(0, 0, S, S, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    const bool no_error = piglit_check_gl_error(GL_NO_ERROR);

    for (int y = 0; y < S; ++y) {
        for (int x = 0; x < S; ++x) {
            const bool depth = passes_depth_test(x);
            const bool alpha = shader_alpha(y) > 0.5f;
            const bool expected = depth && alpha;
            const bool written = pixels[y][x][0] != 0;
            depth_passing += depth;
            alpha_removed += depth && !alpha;
            if (written != expected && wrong++ == 0)
                printf("pixel (%d, %d) %s, expected %s\n", x, y, written ? "written" : "not written",
                       expected ? "written" : "not");
        }
    }
    /* The test means something only if the alpha test removes fragments
     * that passed the depth test. */
    if (alpha_removed == 0 || alpha_removed == depth_passing) {
        printf("the test's setup leaves the alpha test nothing to decide\n");
        piglit_report_result(PIGLIT_FAIL);
    }

    const bool counted = samples == depth_passing;
    if (!counted)
        printf("GL_SAMPLES_PASSED %u, expected %u (the pixels passing the depth test, %u of them removed "
               "by the alpha test after the shader)\n",
               samples, depth_passing, alpha_removed);
    piglit_report_subtest_result(counted && no_error ? PIGLIT_PASS : PIGLIT_FAIL,
                                 "samples-passed-counts-alpha-tested-fragments");
    if (wrong)
        printf("%u pixels wrong: expected %u written (depth test and even row)\n", wrong,
               depth_passing - alpha_removed);
    piglit_report_subtest_result(wrong == 0 && no_error ? PIGLIT_PASS : PIGLIT_FAIL, "alpha-test-follows-shader");
    piglit_report_result(counted && wrong == 0 && no_error ? PIGLIT_PASS : PIGLIT_FAIL);
}
