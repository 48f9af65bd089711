/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: conditional rendering on a tile (spec
 * MESAX_occlusion_unit_async, section 5.X.2): commands execute only when
 * the tile's NOHC > minNohc and NOHC > minRatio * PHC.
 *
 * The pass: depth cleared to 1, an occluder at z 0.25 written over the
 * left 48 columns of a 64 x 64 window, then a quad at z 0.5 over all of
 * it. Tile 0 is the left 32 columns (NOHC 0, PHC 2048), tile 1 the whole
 * window (NOHC 16 * 64 = 1024, PHC 4096, a share of exactly 1/4).
 *
 * Subtests (each draws a red quad over the window under a condition, in
 * RENDER mode with the depth test off, and reads the colour back):
 *   hidden-tile-skips-draw          tile 0, thresholds 0: nothing drawn
 *   visible-tile-draws              tile 1, thresholds 0: drawn
 *   count-threshold-exclusive       tile 1, minNohc 1023 draws, 1024 does not
 *   ratio-threshold-exclusive       tile 1, minRatio 0.25 does not draw (1024 is not
 *                                   > 0.25 * 4096), the float below 0.25 does
 *   clear-is-conditional            glClear under tile 0 clears nothing
 *   no-wait-decides-alike-when-available   QUERY_NO_WAIT, the pass available:
 *                                   the same decisions as QUERY_WAIT
 *   unconditional-after-end         after EndConditionalRenderOcclusionTileMESAX, drawn
 *   pass-in-flight-wait             a condition begun right after the pass ends (its
 *                                   results not yet read) decides the same in QUERY_WAIT
 *   list-compiled-under-condition-draws-when-called  a display list compiled
 *                                   (COMPILE) under tile 0's condition draws when
 *                                   called outside one: the condition is not
 *                                   compiled (issue 12)
 *   list-called-under-condition-is-conditional  the list called under tile 0's
 *                                   condition draws nothing
 */
#include "ou_util.h"

#include <math.h>

enum { W = 64, H = 64 };

static struct ou_async_functions a;
static const unsigned char red[4] = {255, 0, 0, 255};

static void
run_pass(GLuint pass, GLuint (*records)[OU_BRIEF_SIZE])
{
    static const GLint tiles[8] = {0, 0, 32, 64, 0, 0, 64, 64};
    GLuint *buffers[2] = {records[0], records[1]};
    GLsizei sizes[2] = {OU_BRIEF_SIZE, OU_BRIEF_SIZE};

    glEnable(GL_DEPTH_TEST);
    glClear(GL_DEPTH_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(0, 0, 48, H, 0.25f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    OcclusionBuffersMESAX(2, sizes, buffers);
    ScissorsMESAX(2, tiles);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    ou_rect(0, 0, W, H, 0.5f);
    a.EndOcclusionPass();
    ScissorsMESAX(0, NULL);
    glDisable(GL_DEPTH_TEST);
}

/* Clears to black, draws red under the condition; true when drawn. */
static bool
drawn_under(GLuint pass, GLuint tile, GLuint min_nohc, float min_ratio, GLenum mode)
{
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    a.BeginConditionalRenderOcclusionTile(pass, tile, min_nohc, min_ratio, mode);
    glColor4ub(255, 0, 0, 255);
    ou_rect(0, 0, W, H, 0.5f);
    a.EndConditionalRenderOcclusionTile();
    unsigned char pixel[4];
    glReadPixels(W / 2, H / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel);
    return pixel[0] == 255;
}

static void
check(GLuint pass, GLuint tile, GLuint min_nohc, float min_ratio, GLenum mode, bool expected, const char *name)
{
    const bool drawn = drawn_under(pass, tile, min_nohc, min_ratio, mode);
    if (drawn != expected)
        printf("%s: tile %u, minNohc %u, minRatio %.9g: %s, expected %s\n", name, tile, min_nohc, min_ratio,
               drawn ? "drawn" : "not drawn", expected ? "drawn" : "not drawn");
    subtest(drawn == expected && piglit_check_gl_error(GL_NO_ERROR), name);
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
    GLuint pass[2], records[2][OU_BRIEF_SIZE];
    GLint overflowed;

    a = ou_init_async();
    a.GenOcclusionPasses(2, pass);

    /* Right after the pass ends, unread: QUERY_WAIT must wait. */
    run_pass(pass[1], records);
    {
        const bool hidden = drawn_under(pass[1], 0, 0, 0.0f, GL_QUERY_WAIT);
        run_pass(pass[1], records);
        const bool visible = drawn_under(pass[1], 1, 0, 0.0f, GL_QUERY_WAIT);
        subtest(!hidden && visible && piglit_check_gl_error(GL_NO_ERROR), "pass-in-flight-wait");
    }

    run_pass(pass[0], records);
    a.GetOcclusionPassiv(pass[0], GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    if (records[0][OU_NOHC] != 0 || records[0][OU_PHC] != 2048 || records[1][OU_NOHC] != 1024 ||
        records[1][OU_PHC] != 4096) {
        printf("the pass's records are NOHC %u PHC %u and NOHC %u PHC %u, expected 0/2048 and 1024/4096\n",
               records[0][OU_NOHC], records[0][OU_PHC], records[1][OU_NOHC], records[1][OU_PHC]);
        piglit_report_result(PIGLIT_FAIL);
    }

    check(pass[0], 0, 0, 0.0f, GL_QUERY_WAIT, false, "hidden-tile-skips-draw");
    check(pass[0], 1, 0, 0.0f, GL_QUERY_WAIT, true, "visible-tile-draws");
    {
        const bool below = drawn_under(pass[0], 1, 1023, 0.0f, GL_QUERY_WAIT);
        const bool at = drawn_under(pass[0], 1, 1024, 0.0f, GL_QUERY_WAIT);
        subtest(below && !at && piglit_check_gl_error(GL_NO_ERROR), "count-threshold-exclusive");
    }
    {
        const bool at = drawn_under(pass[0], 1, 0, 0.25f, GL_QUERY_WAIT);
        const bool below = drawn_under(pass[0], 1, 0, nextafterf(0.25f, 0.0f), GL_QUERY_WAIT);
        if (at || !below)
            printf("ratio 0.25: %s; ratio just below: %s\n", at ? "drawn" : "not drawn",
                   below ? "drawn" : "not drawn");
        subtest(!at && below && piglit_check_gl_error(GL_NO_ERROR), "ratio-threshold-exclusive");
    }

    /* A clear under a failing condition. */
    glClearColor(1, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glClearColor(0, 0, 0, 1);
    a.BeginConditionalRenderOcclusionTile(pass[0], 0, 0, 0.0f, GL_QUERY_WAIT);
    glClear(GL_COLOR_BUFFER_BIT);
    a.EndConditionalRenderOcclusionTile();
    subtest(ou_probe_rect_rgba_ub(0, 0, W, H, red, 0) && piglit_check_gl_error(GL_NO_ERROR),
            "clear-is-conditional");

    {
        const bool hidden = drawn_under(pass[0], 0, 0, 0.0f, GL_QUERY_NO_WAIT);
        const bool visible = drawn_under(pass[0], 1, 0, 0.0f, GL_QUERY_NO_WAIT);
        const bool ratio = drawn_under(pass[0], 1, 0, 0.25f, GL_QUERY_NO_WAIT);
        subtest(!hidden && visible && !ratio && piglit_check_gl_error(GL_NO_ERROR),
                "no-wait-decides-alike-when-available");
    }

    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    a.BeginConditionalRenderOcclusionTile(pass[0], 0, 0, 0.0f, GL_QUERY_WAIT);
    a.EndConditionalRenderOcclusionTile();
    glColor4ub(255, 0, 0, 255);
    ou_rect(0, 0, W, H, 0.5f);
    subtest(ou_probe_rect_rgba_ub(0, 0, W, H, red, 0) && piglit_check_gl_error(GL_NO_ERROR),
            "unconditional-after-end");

    {
        const GLuint list = glGenLists(1);
        a.BeginConditionalRenderOcclusionTile(pass[0], 0, 0, 0.0f, GL_QUERY_WAIT);
        glNewList(list, GL_COMPILE);
        glColor4ub(255, 0, 0, 255);
        ou_rect(0, 0, W, H, 0.5f);
        glEndList();
        a.EndConditionalRenderOcclusionTile();
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        glCallList(list);
        subtest(ou_probe_rect_rgba_ub(0, 0, W, H, red, 0) && piglit_check_gl_error(GL_NO_ERROR),
                "list-compiled-under-condition-draws-when-called");

        static const unsigned char black[4] = {0, 0, 0, 255};
        glClear(GL_COLOR_BUFFER_BIT);
        a.BeginConditionalRenderOcclusionTile(pass[0], 0, 0, 0.0f, GL_QUERY_WAIT);
        glCallList(list);
        a.EndConditionalRenderOcclusionTile();
        subtest(ou_probe_rect_rgba_ub(0, 0, W, H, black, 0) && piglit_check_gl_error(GL_NO_ERROR),
                "list-called-under-condition-is-conditional");
    }

    piglit_report_result(result);
}
