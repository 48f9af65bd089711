/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: conditional rendering on a tile begun
 * right after the pass ends, in QUERY_WAIT mode, decides on the pass's
 * complete records (spec MESAX_occlusion_unit_async, section 5.X.2), also
 * where the pass's visible fragments are rasterized after the draws under
 * the condition would be. An implementation that keeps the pass and the
 * conditional draw in one batch of work (llvmpipe's scene, rasterized bin
 * by bin in raster order) would decide the first bins before the pass has
 * counted in the later ones.
 *
 * 128 x 128 window (2 x 2 of llvmpipe's 64 x 64 bins), depth cleared to 1.
 * The pass's one tile is the window; it draws an 8 x 8 quad at z 0.5
 * inside one bin-sized quarter of the window. Right after
 * EndOcclusionPassMESAX, with nothing read: BeginConditionalRender-
 * OcclusionTileMESAX(tile 0, thresholds 0, QUERY_WAIT), a red quad over
 * the window with the depth test off, End; then ReadPixels.
 *
 * Subtests, one per quarter holding the quad (so that for any order of
 * bins, the quad lies after the first bin in most of them):
 *   visible-in-{bottom-left,bottom-right,top-left,top-right}-draws-everywhere
 *       the quad visible: every quarter of the window is red
 *   hidden-in-top-right-draws-nowhere
 *       the quad behind an occluder at z 0.25: no quarter is red
 *
 * The test runs on llvmpipe with LP_NUM_THREADS 0, 1, 2 and 8 too
 * (tests/meson.build).
 */
#include "ou_util.h"

enum { S = 128 };

static struct ou_async_functions a;

/* One pixel in each quarter of the window: red or not. */
static bool
quarters_red(bool want, const char *name)
{
    bool ok = true;
    for (int q = 0; q < 4; ++q) {
        const int x = q % 2 ? S - 3 : 2, y = q / 2 ? S - 3 : 2;
        unsigned char p[4];
        glReadPixels(x, y, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, p);
        const bool red = p[0] == 255 && p[1] == 0 && p[2] == 0;
        if (red != want) {
            printf("%s: pixel (%d, %d) is %u %u %u, expected %s\n", name, x, y, p[0], p[1], p[2],
                   want ? "red" : "not red");
            ok = false;
        }
    }
    return ok;
}

static void
run(int qx, int qy, bool hidden, const char *name)
{
    static GLuint record[OU_BRIEF_SIZE];
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    const GLint tile[4] = {0, 0, S, S};
    const float x = qx * 64 + 28, y = qy * 64 + 28;

    GLuint pass;
    a.GenOcclusionPasses(1, &pass);
    glClearColor(0, 0, 0, 1);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    if (hidden) {
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        ou_rect(x - 4, y - 4, x + 12, y + 12, 0.25f);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }
    ou_fill(record, OU_BRIEF_SIZE);
    OcclusionBuffersMESAX(1, sizes, buffers);
    ScissorsMESAX(1, tile);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    ou_rect(x, y, x + 8, y + 8, 0.5f);
    a.EndOcclusionPass();
    ScissorsMESAX(0, NULL);

    glDisable(GL_DEPTH_TEST);
    a.BeginConditionalRenderOcclusionTile(pass, 0, 0, 0.0f, GL_QUERY_WAIT);
    glColor4ub(255, 0, 0, 255);
    ou_rect(0, 0, S, S, 0.5f);
    a.EndConditionalRenderOcclusionTile();
    glColor4ub(255, 255, 255, 255);
    const bool drawn_right = quarters_red(!hidden, name);

    GLint overflowed = -1;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    const GLuint want = hidden ? 0 : 64;
    if (record[OU_NOHC] != want || record[OU_PHC] != 64)
        printf("%s: NOHC %u PHC %u, expected %u and 64\n", name, record[OU_NOHC], record[OU_PHC], want);
    subtest(drawn_right && overflowed == 0 && record[OU_NOHC] == want && record[OU_PHC] == 64 &&
                piglit_check_gl_error(GL_NO_ERROR),
            name);
    a.DeleteOcclusionPasses(1, &pass);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
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
    a = ou_init_async();
    run(0, 0, false, "visible-in-bottom-left-draws-everywhere");
    run(1, 0, false, "visible-in-bottom-right-draws-everywhere");
    run(0, 1, false, "visible-in-top-left-draws-everywhere");
    run(1, 1, false, "visible-in-top-right-draws-everywhere");
    run(1, 1, true, "hidden-in-top-right-draws-nowhere");
    piglit_report_result(result);
}
