/*
 * GL_MESAX_occlusion_unit and EXT_depth_bounds_test (spec section 4.1,
 * issue 20, "Dependencies on EXT_depth_bounds_test"): the depth bounds
 * test follows PHC, so a fragment that fails it counts in PHC and not in
 * NOHC, as one failing the depth buffer test does.
 *
 * A 64 x 32 window, depth 1.0 but 0.25 over the left half; the pass draws
 * a window-sized rectangle at z 0.5 with the depth bounds [0, 0.5], which
 * only the left half's stored depth lies in.
 *
 * Subtests:
 *   bounds-failures-count-in-phc-only   depth test off: NOHC 1024 (the left
 *                                       half), PHC 2048, box x 0..31
 *   bounds-and-depth-test               depth test LESS as well: the left half
 *                                       fails the depth test, the right half the
 *                                       bounds: NOHC 0, PHC 2048
 *   samples-passed-agrees               a SAMPLES_PASSED query around the first
 *                                       pass's draw counts its NOHC
 *
 * softpipe exposes EXT_depth_bounds_test, which this test requires there;
 * llvmpipe does not, and there the test skips.
 */
#include "ou_util.h"

enum { W = 64, H = 32 };

typedef void (*DepthBoundsProc)(GLclampd zmin, GLclampd zmax);

static GLuint query;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;

static void
draw_rectangle(void)
{
    BeginQuery(GL_SAMPLES_PASSED, query);
    ou_rect(0, 0, W, H, 0.5f);
    EndQuery(GL_SAMPLES_PASSED);
}

int main(int argc, char **argv)
{
    ou_init(argc, argv, W, H);
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    if (!piglit_is_extension_supported("GL_EXT_depth_bounds_test")) {
        printf("%s does not expose GL_EXT_depth_bounds_test\n", renderer);
        if (renderer && strstr(renderer, "softpipe"))
            piglit_report_result(PIGLIT_FAIL);
        piglit_report_result(PIGLIT_SKIP);
    }
    DepthBoundsProc DepthBoundsEXT = (DepthBoundsProc)piglit_get_proc_address("glDepthBoundsEXT");
    PFNGLGENQUERIESPROC GenQueries = (PFNGLGENQUERIESPROC)piglit_get_proc_address("glGenQueries");
    PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv =
        (PFNGLGETQUERYOBJECTUIVPROC)piglit_get_proc_address("glGetQueryObjectuiv");
    BeginQuery = (PFNGLBEGINQUERYPROC)piglit_get_proc_address("glBeginQuery");
    EndQuery = (PFNGLENDQUERYPROC)piglit_get_proc_address("glEndQuery");
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
    GLuint rec[1][OU_BRIEF_SIZE];

    glDisable(GL_DEPTH_TEST);
    ou_brief_pass(0, NULL, rec, draw_rectangle);
    GLuint samples = ~0u;
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    const GLuint left[OU_BRIEF_SIZE] = {W / 2 * H, W * H, 0, W / 2 - 1, 0, H - 1, ou_depth(0.5), ou_depth(0.5)};
    subtest(ou_check_record("bounds-failures-count-in-phc-only", rec[0], left, 0) &&
                piglit_check_gl_error(GL_NO_ERROR),
            "bounds-failures-count-in-phc-only");
    if (samples != rec[0][OU_NOHC])
        printf("SAMPLES_PASSED %u, NOHC %u\n", samples, rec[0][OU_NOHC]);
    subtest(samples == W / 2 * H && samples == rec[0][OU_NOHC], "samples-passed-agrees");

    glEnable(GL_DEPTH_TEST);
    ou_brief_pass(0, NULL, rec, draw_rectangle);
    const GLuint none[OU_BRIEF_SIZE] = {0, W * H, OU_EMPTY_MIN, OU_EMPTY_MAX, OU_EMPTY_MIN, OU_EMPTY_MAX,
                                        OU_EMPTY_MIN, OU_EMPTY_MAX};
    subtest(ou_check_record("bounds-and-depth-test", rec[0], none, 0) && piglit_check_gl_error(GL_NO_ERROR),
            "bounds-and-depth-test");
    piglit_report_result(result);
}
