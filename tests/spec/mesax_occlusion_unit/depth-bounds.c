/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit and EXT_depth_bounds_test (spec section 4.1,
 * issue 20, "Dependencies on EXT_depth_bounds_test"): the depth bounds
 * test is one of the per-fragment tests PHC counts before, so a fragment
 * that fails it counts in PHC and not in NOHC, as one failing the depth
 * buffer test does, and as GL_SAMPLES_PASSED does not count it.
 *
 * A 64 x 32 window, depth 1.0 but 0.25 over the left half; the depth
 * bounds are [0, 0.5], which only the left half's stored depth lies in.
 * Each pass draws a window-sized rectangle.
 *
 * Subtests:
 *   bounds-failures-count-in-phc-only   depth test off, rectangle at z 0.5:
 *                                       NOHC 1024 (the left half), PHC 2048,
 *                                       box x 0..31
 *   samples-passed-agrees               a SAMPLES_PASSED query around that
 *                                       pass's draw counts its NOHC
 *   bounds-fail-with-depth-test-passing depth test LESS, rectangle at z 0.125,
 *                                       which passes it everywhere: NOHC 1024,
 *                                       PHC 2048, box x 0..31, and the same
 *                                       draw's SAMPLES_PASSED in RENDER mode
 *                                       (depth writes off) is 1024
 *   bounds-and-depth-test               depth test LESS, rectangle at z 0.5: the
 *                                       left half fails the depth test, the
 *                                       right half the bounds: NOHC 0, PHC 2048
 *   bounds-disabled-counts-all          bounds test off, depth test LESS,
 *                                       rectangle at z 0.125: NOHC 2048
 *
 * softpipe exposes EXT_depth_bounds_test, which this test requires there;
 * llvmpipe of Mesa 22.3 does not, and there the test skips, saying so (the
 * spec's dependency section then does not apply).
 */
#include "ou_util.h"

enum { W = 64, H = 32 };

typedef void (*DepthBoundsProc)(GLclampd zmin, GLclampd zmax);

static GLuint query;
static float rectangle_z;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;

static void
draw_rectangle(void)
{
    BeginQuery(GL_SAMPLES_PASSED, query);
    ou_rect(0, 0, W, H, rectangle_z);
    EndQuery(GL_SAMPLES_PASSED);
}

static GLuint
samples_passed(void)
{
    GLuint samples = 0xdeadbeefu;
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    return samples;
}

static void
expect_record(const char *name, const GLuint expected[OU_BRIEF_SIZE])
{
    GLuint rec[1][OU_BRIEF_SIZE];
    ou_brief_pass(0, NULL, rec, draw_rectangle);
    subtest(ou_check_record(name, rec[0], expected, 0) && piglit_check_gl_error(GL_NO_ERROR), name);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = W;
    config.window_height = H;
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
    ou_init();
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    if (!piglit_is_extension_supported("GL_EXT_depth_bounds_test")) {
        printf("%s does not expose GL_EXT_depth_bounds_test: the spec's interaction with it does not apply\n",
               renderer);
        if (renderer && strstr(renderer, "softpipe"))
            piglit_report_result(PIGLIT_FAIL);
        piglit_report_result(PIGLIT_SKIP);
    }
    DepthBoundsProc DepthBoundsEXT = glDepthBoundsEXT;
    PFNGLGENQUERIESPROC GenQueries = glGenQueries;
    GetQueryObjectuiv = glGetQueryObjectuiv;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    if (!DepthBoundsEXT || !GenQueries || !GetQueryObjectuiv || !BeginQuery || !EndQuery) {
        printf("glDepthBoundsEXT or a query entry point is missing\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    GenQueries(1, &query);

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(0, 0, W / 2, H, 0.25f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

    glEnable(GL_DEPTH_BOUNDS_TEST_EXT);
    DepthBoundsEXT(0.0, 0.5);

    /* Depth test off: only the bounds discard. */
    glDisable(GL_DEPTH_TEST);
    rectangle_z = 0.5f;
    const GLuint left_at_half[OU_BRIEF_SIZE] = {W / 2 * H, W * H, 0, W / 2 - 1, 0, H - 1,
                                                ou_depth(0.5), ou_depth(0.5)};
    expect_record("bounds-failures-count-in-phc-only", left_at_half);
    const GLuint in_pass = samples_passed();
    if (in_pass != W / 2 * H)
        printf("SAMPLES_PASSED in the pass %u, expected %d\n", in_pass, W / 2 * H);
    subtest(in_pass == W / 2 * H, "samples-passed-agrees");

    /* Depth test on and passing everywhere: the bounds alone discard the
     * right half, in the pass and in RENDER mode. */
    glEnable(GL_DEPTH_TEST);
    rectangle_z = 0.125f;
    const GLuint left_in_front[OU_BRIEF_SIZE] = {W / 2 * H, W * H, 0, W / 2 - 1, 0, H - 1,
                                                 ou_depth(0.125), ou_depth(0.125)};
    GLuint rec[1][OU_BRIEF_SIZE];
    ou_brief_pass(0, NULL, rec, draw_rectangle);
    bool ok = ou_check_record("bounds-fail-with-depth-test-passing", rec[0], left_in_front, 0);
    glDepthMask(GL_FALSE); /* the buffer keeps its two halves */
    draw_rectangle();
    glDepthMask(GL_TRUE);
    const GLuint in_render = samples_passed();
    if (in_render != W / 2 * H)
        printf("SAMPLES_PASSED in RENDER mode %u, expected %d\n", in_render, W / 2 * H);
    subtest(ok && in_render == W / 2 * H && piglit_check_gl_error(GL_NO_ERROR),
            "bounds-fail-with-depth-test-passing");

    /* Each half fails one test. */
    rectangle_z = 0.5f;
    const GLuint none[OU_BRIEF_SIZE] = {0, W * H, OU_EMPTY_MIN, OU_EMPTY_MAX, OU_EMPTY_MIN, OU_EMPTY_MAX,
                                        OU_EMPTY_MIN, OU_EMPTY_MAX};
    expect_record("bounds-and-depth-test", none);

    /* The bounds test off: every fragment in front passes. */
    glDisable(GL_DEPTH_BOUNDS_TEST_EXT);
    rectangle_z = 0.125f;
    const GLuint all[OU_BRIEF_SIZE] = {W * H, W * H, 0, W - 1, 0, H - 1, ou_depth(0.125), ou_depth(0.125)};
    expect_record("bounds-disabled-counts-all", all);
    piglit_report_result(result);
}
