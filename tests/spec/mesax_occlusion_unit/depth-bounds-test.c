/*
 * GL_MESAX_occlusion_unit and EXT_depth_bounds_test: the depth bounds test
 * is one of the per-fragment tests (spec, "Dependencies on
 * EXT_depth_bounds_test"): a fragment that fails it has entered the tests,
 * so it counts in PHC, and would not change the framebuffer, so it does not
 * count in NOHC, exactly as GL_SAMPLES_PASSED does not count it.
 *
 * A 16 x 16 quad at depth 0.25, depth test LESS, over a depth buffer whose
 * left half holds 0.5 and right half 0.75; bounds [0.6, 1.0] test the
 * buffer's depth, so the left half fails them.
 *
 * Subtests:
 *   bounds-fail-counts-phc-not-nohc   PHC 256, NOHC 128 (the right half), box
 *                                     x 8..15, and SAMPLES_PASSED in RENDER 128
 *   bounds-disabled-counts-all        bounds test off: NOHC 256
 *
 * llvmpipe of Mesa 22.3 does not expose EXT_depth_bounds_test (softpipe
 * does): there the test skips, saying so; the dependency section then does
 * not apply.
 */
#include "ou_util.h"

#define S 16

static PFNGLDEPTHBOUNDSEXTPROC DepthBoundsEXT;

static void
paint_depth(void)
{
    glDepthFunc(GL_ALWAYS);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(0, 0, S / 2, S, 0.5f);
    ou_rect(S / 2, 0, S, S, 0.75f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_LESS);
}

static void
quad(void)
{
    ou_rect(0, 0, S, S, 0.25f);
}

int
main(int argc, char **argv)
{
    ou_init(argc, argv, S, S);
    DepthBoundsEXT = (PFNGLDEPTHBOUNDSEXTPROC)piglit_get_proc_address("glDepthBoundsEXT");
    if (!piglit_is_extension_supported("GL_EXT_depth_bounds_test") || !DepthBoundsEXT) {
        printf("%s does not expose GL_EXT_depth_bounds_test: the spec's interaction with it does not apply\n",
               (const char *)glGetString(GL_RENDERER));
        piglit_report_result(PIGLIT_SKIP);
    }
    PFNGLGENQUERIESPROC GenQueries = (PFNGLGENQUERIESPROC)piglit_get_proc_address("glGenQueries");
    PFNGLBEGINQUERYPROC BeginQuery = (PFNGLBEGINQUERYPROC)piglit_get_proc_address("glBeginQuery");
    PFNGLENDQUERYPROC EndQuery = (PFNGLENDQUERYPROC)piglit_get_proc_address("glEndQuery");
    PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv =
        (PFNGLGETQUERYOBJECTUIVPROC)piglit_get_proc_address("glGetQueryObjectuiv");

    glEnable(GL_DEPTH_TEST);
    glClear(GL_DEPTH_BUFFER_BIT);
    paint_depth();
    DepthBoundsEXT(0.6, 1.0);
    glEnable(GL_DEPTH_BOUNDS_TEST_EXT);
    GLuint record[1][OU_BRIEF_SIZE];
    ou_brief_pass(0, NULL, record, quad);
    const GLuint z = ou_depth(0.25);
    const GLuint expected[OU_BRIEF_SIZE] = {S * S / 2, S * S, S / 2, S - 1, 0, S - 1, z, z};
    bool ok = ou_check_record("bounds-fail-counts-phc-not-nohc", record[0], expected, 0);

    GLuint query, samples = 0xdeadbeefu;
    GenQueries(1, &query);
    glDepthMask(GL_FALSE);   /* the buffer keeps its two halves */
    BeginQuery(GL_SAMPLES_PASSED, query);
    quad();
    EndQuery(GL_SAMPLES_PASSED);
    glDepthMask(GL_TRUE);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    if (samples != S * S / 2)
        printf("SAMPLES_PASSED in RENDER mode is %u, expected %d\n", samples, S * S / 2);
    subtest(ok && samples == S * S / 2 && piglit_check_gl_error(GL_NO_ERROR), "bounds-fail-counts-phc-not-nohc");

    glDisable(GL_DEPTH_BOUNDS_TEST_EXT);
    ou_brief_pass(0, NULL, record, quad);
    const GLuint all[OU_BRIEF_SIZE] = {S * S, S * S, 0, S - 1, 0, S - 1, z, z};
    subtest(ou_check_record("bounds-disabled-counts-all", record[0], all, 0) && piglit_check_gl_error(GL_NO_ERROR),
            "bounds-disabled-counts-all");
    piglit_report_result(result);
}
