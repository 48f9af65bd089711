/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: the default tile of a viewport whose bounds are
 * not integers (ViewportIndexedf, ARB_viewport_array) is the set of pixels
 * whose centres the viewport covers, its edges included (spec section 5.X:
 * x + 1/2 in [xv, xv + w], y + 1/2 in [yv, yv + h]), the pixels
 * rasterization can produce for primitives inside it; so a quad over the
 * whole clip volume counts in the default tile every fragment it produces,
 * as many as GL_SAMPLES_PASSED counts for it in RENDER mode.
 *
 * The window is 64 x 32; the quad covers clip space [-1, 1]^2 at depth 0.5,
 * with the depth test off.
 *
 * Subtests where no viewport edge passes through a pixel centre:
 *   fractional-width    viewport (0, 0, 10.75, 32): 11 columns, NOHC = PHC =
 *                       352 = GL_SAMPLES_PASSED, box 0..10 x 0..31
 *   fractional-origin   viewport (2.25, 3.25, 5.5, 6.5): columns 2..7, rows
 *                       3..9, 42 = GL_SAMPLES_PASSED, box 2..7 x 3..9
 *
 * Subtests where an edge does (edge-centre-*): GL lets a rasterizer produce
 * a fragment whose centre lies on the viewport's edge or not (softpipe does
 * on the right and top edges, llvmpipe does not), so the expected record is
 * what RENDER mode drew: NOHC = PHC = GL_SAMPLES_PASSED = the pixels
 * written, and the box the box of those pixels (glReadPixels). Each
 * viewport is tried with the clip-volume quad and with a strip a quarter
 * pixel wide along its right edge and along its top edge, whose only
 * candidate fragments are those with centres on that edge.
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

static float strip_x0 = -1, strip_y0 = -1;

static void
edge_strip(void)
{
    ou_rect(strip_x0, strip_y0, 1, 1, 0);
}

/* Draws `draw` in RENDER mode into a cleared colour buffer and returns the
 * record it should give: the pixels it wrote and their box, the depth of
 * the quad; *samples is GL_SAMPLES_PASSED over the same draw. */
static void
rendered_record(void (*draw)(void), GLuint expected[OU_BRIEF_SIZE], GLuint *samples)
{
    GLuint query;

    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glColor4f(1, 1, 1, 1);
    GenQueries(1, &query);
    BeginQuery(GL_SAMPLES_PASSED, query);
    draw();
    EndQuery(GL_SAMPLES_PASSED);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, samples);
    ou_record_of_drawn_pixels(W, H, 0.5, expected);
}

static bool
check_drawn(const char *name, void (*draw)(void))
{
    GLuint expected[OU_BRIEF_SIZE], record[1][OU_BRIEF_SIZE], samples = 0xdeadbeefu;

    rendered_record(draw, expected, &samples);
    const GLint overflowed = ou_brief_pass(0, NULL, record, draw);
    bool ok = ou_check_record(name, record[0], expected, OU_Z24_READBACK_TOLERANCE);
    if (samples != expected[OU_NOHC]) {
        printf("%s: GL_SAMPLES_PASSED is %u, %u pixels written\n", name, samples, expected[OU_NOHC]);
        ok = false;
    }
    return ok && overflowed == 0;
}

static void
check_edge_centres(const char *name, float x, float y, float w, float h)
{
    char what[128];
    bool ok = true;

    ViewportIndexedf(0, x, y, w, h);
    snprintf(what, sizeof(what), "%s, clip-volume quad", name);
    ok = check_drawn(what, clip_volume_quad) && ok;
    /* A strip from a quarter pixel inside the right edge to it. */
    strip_x0 = 1.0f - 2.0f * 0.25f / w;
    strip_y0 = -1.0f;
    snprintf(what, sizeof(what), "%s, right-edge strip", name);
    ok = check_drawn(what, edge_strip) && ok;
    strip_x0 = -1.0f;
    strip_y0 = 1.0f - 2.0f * 0.25f / h;
    snprintf(what, sizeof(what), "%s, top-edge strip", name);
    ok = check_drawn(what, edge_strip) && ok;
    subtest(ok && piglit_check_gl_error(GL_NO_ERROR), name);
}

static const struct {
    const char *name;
    float x, y, w, h;
} edge_centre_viewports[] = {
    {"edge-centre-right", 0.0f, 0.0f, 10.5f, 32.0f},
    {"edge-centre-left-and-right", 0.5f, 0.0f, 10.0f, 32.0f},
    {"edge-centre-top", 0.0f, 0.0f, 64.0f, 10.5f},
    {"edge-centre-bottom-and-top", 0.0f, 0.5f, 64.0f, 10.0f},
    {"edge-centre-every-edge", 2.5f, 3.5f, 7.0f, 9.0f},
};

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
    const GLuint z = ou_depth(0.5);
    const GLuint width[OU_BRIEF_SIZE] = {11 * 32, 11 * 32, 0, 10, 0, 31, z, z};
    const GLuint origin[OU_BRIEF_SIZE] = {6 * 7, 6 * 7, 2, 7, 3, 9, z, z};

    ou_init();
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_DEPTH_TEST);
    GenQueries = glGenQueries;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    GetQueryObjectuiv = glGetQueryObjectuiv;
    ViewportIndexedf = glViewportIndexedf;
    if (!piglit_is_extension_supported("GL_ARB_viewport_array") || !ViewportIndexedf) {
        ou_subtest_dependency_missing("fractional-width", "GL_ARB_viewport_array");
        ou_subtest_dependency_missing("fractional-origin", "GL_ARB_viewport_array");
        for (unsigned i = 0; i < sizeof(edge_centre_viewports) / sizeof(edge_centre_viewports[0]); ++i)
            ou_subtest_dependency_missing(edge_centre_viewports[i].name, "GL_ARB_viewport_array");
        piglit_report_result(result);
    }

    check_viewport("fractional-width", 0.0f, 0.0f, 10.75f, 32.0f, width);
    check_viewport("fractional-origin", 2.25f, 3.25f, 5.5f, 6.5f, origin);
    for (unsigned i = 0; i < sizeof(edge_centre_viewports) / sizeof(edge_centre_viewports[0]); ++i)
        check_edge_centres(edge_centre_viewports[i].name, edge_centre_viewports[i].x,
                           edge_centre_viewports[i].y, edge_centre_viewports[i].w,
                           edge_centre_viewports[i].h);
    piglit_report_result(result);
}
