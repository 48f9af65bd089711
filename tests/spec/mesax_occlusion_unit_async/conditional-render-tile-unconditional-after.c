/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: the commands after a draw that a tile
 * condition discarded, once EndConditionalRenderOcclusionTileMESAX has
 * ended the condition, execute (spec MESAX_occlusion_unit_async, section
 * 5.X.2: only rendering commands between Begin and End are conditional).
 * Occlusion queries begun or ended under a condition are not rendering
 * commands: they begin and end whatever the condition decides.
 *
 * The condition is begun while its pass is still rasterizing (a pass of
 * many quads, not read), which is when llvmpipe with rasterizer threads
 * bins the conditional draw and decides it in the rasterizer; then the
 * decision must cover the discarded draw and nothing binned after it.
 *
 * The pass: depth cleared to 1, an occluder at z 0.25 over the left half
 * of a 256 x 256 window (4 x 4 of llvmpipe's 64 x 64 bins), then the
 * quads of the pass at z 0.5. Tile 0 is the left half (NOHC 0), so a
 * condition on it with thresholds 0 discards.
 *
 * Subtests (each begins the pass anew, then a condition on tile 0, a
 * green full-window quad under it, the end of the condition):
 *   discarded-draw-draws-nothing    no green pixel (the condition decides)
 *   clear-after-discarded-draw      a glClear of colour and depth after it
 *                                   clears every pixel
 *   draw-after-discarded-draw       a red full-window quad after it covers
 *                                   every pixel
 *   query-after-discarded-draw      SAMPLES_PASSED around a full-window quad
 *                                   after it is 65536, and around an 8 x 8
 *                                   quad after that 64
 *   query-begun-under-condition     a query begun under the condition and
 *                                   ended after it counts the 8 x 8 quad
 *                                   drawn after it: 64
 */
#include "ou_util.h"

enum { W = 256, H = 256, PASS_QUADS = 64 };

static struct ou_async_functions a;
static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;

static const unsigned char red[4] = {255, 0, 0, 255};
static const unsigned char blue[4] = {0, 0, 255, 255};

/* Begins the pass of tile 0 (hidden) and tile 1 (the whole window) and
 * ends it without reading it: its scenes may still be rasterizing. */
static void
run_pass(GLuint pass)
{
    static GLuint records[2][OU_BRIEF_SIZE];
    static const GLint tiles[8] = {0, 0, W / 2, H, 0, 0, W, H};
    GLuint *buffers[2] = {records[0], records[1]};
    GLsizei sizes[2] = {OU_BRIEF_SIZE, OU_BRIEF_SIZE};

    glEnable(GL_DEPTH_TEST);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(0, 0, W / 2, H, 0.25f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    OcclusionBuffersMESAX(2, sizes, buffers);
    ScissorsMESAX(2, tiles);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    for (int i = 0; i < PASS_QUADS; ++i)
        ou_rect(0, 0, W, H, 0.5f);
    a.EndOcclusionPass();
    ScissorsMESAX(0, NULL);
    glDisable(GL_DEPTH_TEST);
}

/* The window blue, the pass anew, a green quad under the hidden tile's
 * condition, the condition ended. */
static void
discarded_draw(GLuint pass)
{
    glClearColor(0, 0, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    run_pass(pass);
    a.BeginConditionalRenderOcclusionTile(pass, 0, 0, 0.0f, GL_QUERY_WAIT);
    glColor4ub(0, 255, 0, 255);
    ou_rect(0, 0, W, H, 0.5f);
    a.EndConditionalRenderOcclusionTile();
}

static GLuint
query_result(GLuint query)
{
    GLuint samples = 0xdeadbeefu;
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    return samples;
}

static bool
depth_everywhere(float expected)
{
    static float depth[W * H];
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    for (int i = 0; i < W * H; ++i) {
        if (depth[i] != expected) {
            printf("depth at (%d, %d) is %g, expected %g\n", i % W, i / W, depth[i], expected);
            return false;
        }
    }
    return true;
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
    GLuint pass, query[2];

    a = ou_init_async();
    GenQueries = glGenQueries;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    GetQueryObjectuiv = glGetQueryObjectuiv;
    if (!GenQueries || !BeginQuery || !EndQuery || !GetQueryObjectuiv) {
        ou_subtest_unsupported("query-after-discarded-draw", "OpenGL 1.5 occlusion queries");
        piglit_report_result(result);
    }
    a.GenOcclusionPasses(1, &pass);
    GenQueries(2, query);

    discarded_draw(pass);
    subtest(ou_probe_rect_rgba_ub(0, 0, W, H, blue, 0) && piglit_check_gl_error(GL_NO_ERROR),
            "discarded-draw-draws-nothing");

    discarded_draw(pass);
    glClearColor(1, 0, 0, 1);
    glClearDepth(0.75);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    {
        const bool colour = ou_probe_rect_rgba_ub(0, 0, W, H, red, 0);
        const bool depth = depth_everywhere(0.75f);
        subtest(colour && depth && piglit_check_gl_error(GL_NO_ERROR), "clear-after-discarded-draw");
    }

    discarded_draw(pass);
    glColor4ub(255, 0, 0, 255);
    ou_rect(0, 0, W, H, 0.5f);
    subtest(ou_probe_rect_rgba_ub(0, 0, W, H, red, 0) && piglit_check_gl_error(GL_NO_ERROR),
            "draw-after-discarded-draw");

    discarded_draw(pass);
    BeginQuery(GL_SAMPLES_PASSED, query[0]);
    ou_rect(0, 0, W, H, 0.5f);
    EndQuery(GL_SAMPLES_PASSED);
    BeginQuery(GL_SAMPLES_PASSED, query[1]);
    ou_rect(0, 0, 8, 8, 0.5f);
    EndQuery(GL_SAMPLES_PASSED);
    {
        const GLuint whole = query_result(query[0]), small = query_result(query[1]);
        if (whole != W * H || small != 64)
            printf("SAMPLES_PASSED %u for the window (expected %d), %u for 8 x 8 (expected 64)\n", whole, W * H,
                   small);
        subtest(whole == W * H && small == 64 && piglit_check_gl_error(GL_NO_ERROR), "query-after-discarded-draw");
    }

    glClearColor(0, 0, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    run_pass(pass);
    a.BeginConditionalRenderOcclusionTile(pass, 0, 0, 0.0f, GL_QUERY_WAIT);
    BeginQuery(GL_SAMPLES_PASSED, query[0]);
    ou_rect(0, 0, W, H, 0.5f);
    a.EndConditionalRenderOcclusionTile();
    ou_rect(0, 0, 8, 8, 0.5f);
    EndQuery(GL_SAMPLES_PASSED);
    {
        const GLuint samples = query_result(query[0]);
        if (samples != 64)
            printf("SAMPLES_PASSED %u, expected 64 (the 8 x 8 quad after the condition)\n", samples);
        subtest(samples == 64 && piglit_check_gl_error(GL_NO_ERROR), "query-begun-under-condition");
    }

    piglit_report_result(result);
}
