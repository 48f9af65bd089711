/*
 * GL_MESAX_occlusion_unit: the default tile of a viewport whose bounds are
 * not integers (ViewportIndexedf, ARB_viewport_array) is the set of pixels
 * whose centres the viewport covers (spec section 5.X: x + 1/2 in
 * [xv, xv + w), y + 1/2 in [yv, yv + h)), the pixels rasterization can
 * produce for primitives inside it; so a quad over the whole clip volume
 * counts in the default tile every fragment it produces, as many as
 * GL_SAMPLES_PASSED counts for it in RENDER mode.
 *
 * The window is 64 x 32; the quad covers clip space [-1, 1]^2 at depth 0.5,
 * with the depth test off. No viewport edge passes through a pixel centre.
 *
 * Subtests:
 *   fractional-width    viewport (0, 0, 10.75, 32): 11 columns, NOHC = PHC =
 *                       352 = GL_SAMPLES_PASSED, box 0..10 x 0..31
 *   fractional-origin   viewport (2.25, 3.25, 5.5, 6.5): columns 2..7, rows
 *                       3..9, 42 = GL_SAMPLES_PASSED, box 2..7 x 3..9
 */
#include "ou_util.h"

enum { W = 64, H = 32 };

static PFNGLVIEWPORTINDEXEDFPROC ViewportIndexedf;
static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;

static void
clip_volume_quad(void)
{
    ou_rect(-1, -1, 1, 1, 0);
}

static void
check_viewport(const char *name, float x, float y, float w, float h, const GLuint expected[OU_BRIEF_SIZE])
{
    GLuint record[1][OU_BRIEF_SIZE], query, samples = 0xdeadbeefu;

    ViewportIndexedf(0, x, y, w, h);
    GenQueries(1, &query);
    BeginQuery(GL_SAMPLES_PASSED, query);
    clip_volume_quad();
    EndQuery(GL_SAMPLES_PASSED);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);

    const GLint overflowed = ou_brief_pass(0, NULL, record, clip_volume_quad);
    bool ok = ou_check_record(name, record[0], expected, OU_Z24_READBACK_TOLERANCE);
    if (samples != expected[OU_NOHC]) {
        printf("%s: GL_SAMPLES_PASSED is %u, expected %u\n", name, samples, expected[OU_NOHC]);
        ok = false;
    }
    subtest(ok && overflowed == 0 && piglit_check_gl_error(GL_NO_ERROR), name);
}

int
main(int argc, char **argv)
{
    const GLuint z = ou_depth(0.5);
    const GLuint width[OU_BRIEF_SIZE] = {11 * 32, 11 * 32, 0, 10, 0, 31, z, z};
    const GLuint origin[OU_BRIEF_SIZE] = {6 * 7, 6 * 7, 2, 7, 3, 9, z, z};

    ou_init(argc, argv, W, H);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_DEPTH_TEST);
    GenQueries = (PFNGLGENQUERIESPROC)piglit_get_proc_address("glGenQueries");
    BeginQuery = (PFNGLBEGINQUERYPROC)piglit_get_proc_address("glBeginQuery");
    EndQuery = (PFNGLENDQUERYPROC)piglit_get_proc_address("glEndQuery");
    GetQueryObjectuiv = (PFNGLGETQUERYOBJECTUIVPROC)piglit_get_proc_address("glGetQueryObjectuiv");
    ViewportIndexedf = (PFNGLVIEWPORTINDEXEDFPROC)piglit_get_proc_address("glViewportIndexedf");
    if (!piglit_is_extension_supported("GL_ARB_viewport_array") || !ViewportIndexedf) {
        ou_subtest_dependency_missing("fractional-width", "GL_ARB_viewport_array");
        ou_subtest_dependency_missing("fractional-origin", "GL_ARB_viewport_array");
        piglit_report_result(result);
    }

    check_viewport("fractional-width", 0.0f, 0.0f, 10.75f, 32.0f, width);
    check_viewport("fractional-origin", 2.25f, 3.25f, 5.5f, 6.5f, origin);
    piglit_report_result(result);
}
