/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_conservative: where the conservative mode is
 * accepted and what its records and tile conditions do (spec, sections
 * 5.X, 5.X.1 and 5.X.2 as the extension amends them; Errors).
 *
 * The scene: a 64 x 64 window, depth cleared to 1, an occluder at z 0.25
 * written over the left 48 columns, then a quad at z 0.5 over the window.
 * Tile 0 is the left 32 columns (hidden), tile 1 the whole window (1024
 * pixels visible).
 *
 * Subtests:
 *   render-mode-state        RENDER_MODE is CONSERVATIVE_OCCLUSION_MESAX
 *                            inside the mode; RenderMode returns 0 leaving it
 *   render-mode-records      tile 0 answers 0, tile 1 answers 1; words 1-7
 *                            keep the application's values
 *   pass-object-records      the same through BeginOcclusionPassMESAX and
 *                            GetOcclusionPassivMESAX
 *   condition-refuses-count  minNohc 1: INVALID_OPERATION, conditional
 *                            rendering not begun (End then errs, a draw is
 *                            unconditional)
 *   condition-refuses-ratio  minRatio 0.5: the same
 *   condition-decides        with 0 and 0.0, a draw under tile 0 draws
 *                            nothing, under tile 1 draws
 */
#include "ou_util.h"

enum { W = 64, H = 64 };
#define SENTINEL 0x5a5a5a5au

static struct ou_async_functions a;
static const GLint tiles[8] = {0, 0, 32, 64, 0, 0, 64, 64};
static GLuint records[2][OU_BRIEF_SIZE];

static void
set_up_scene(void)
{
    GLuint *buffers[2] = {records[0], records[1]};
    GLsizei sizes[2] = {OU_BRIEF_SIZE, OU_BRIEF_SIZE};
    for (int i = 0; i < 2; ++i)
        for (int w = 0; w < OU_BRIEF_SIZE; ++w)
            records[i][w] = SENTINEL;
    glEnable(GL_DEPTH_TEST);
    glClear(GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(0, 0, 48, H, 0.25f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    OcclusionBuffersMESAX(2, sizes, buffers);
    ScissorsMESAX(2, tiles);
}

static bool
records_are(GLuint hidden, GLuint visible, const char *how)
{
    bool ok = records[0][0] == hidden && records[1][0] == visible;
    if (!ok)
        printf("%s: tile answers %#x and %#x, expected %u and %u\n", how, records[0][0], records[1][0],
               hidden, visible);
    for (int i = 0; i < 2; ++i) {
        for (int w = 1; w < OU_BRIEF_SIZE; ++w) {
            if (records[i][w] != SENTINEL) {
                printf("%s: tile %d word %d changed to %#x\n", how, i, w, records[i][w]);
                ok = false;
            }
        }
    }
    return ok;
}

/* Clears the colour buffer; outside conditional rendering, since a Clear
 * under a condition is itself conditional. */
static void
clear_colour(void)
{
    glClear(GL_COLOR_BUFFER_BIT);
}

/* Draws a red quad over the window with the depth test off and reports
 * whether it reached the pixel (40, 10), cleared before by clear_colour. */
static bool
red_quad_drawn(void)
{
    static const float red[4] = {1, 0, 0, 1};
    glDisable(GL_DEPTH_TEST);
    glColor4fv(red);
    ou_rect(0, 0, W, H, 0.5f);
    glColor4f(1, 1, 1, 1);
    unsigned char pixel[4];
    glReadPixels(40, 10, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel);
    return pixel[0] == 255 && pixel[1] == 0;
}

/* A condition refused: INVALID_OPERATION, and none begun. */
static void
condition_refused(GLuint pass, GLuint min_nohc, GLfloat min_ratio, const char *name)
{
    clear_colour();
    a.BeginConditionalRenderOcclusionTile(pass, 0, min_nohc, min_ratio, GL_QUERY_WAIT);
    bool ok = piglit_check_gl_error(GL_INVALID_OPERATION);
    /* Tile 0 is hidden: a condition begun would discard the draw. */
    if (!red_quad_drawn()) {
        printf("%s: a draw after the refused condition was discarded\n", name);
        ok = false;
    }
    a.EndConditionalRenderOcclusionTile();
    ok = piglit_check_gl_error(GL_INVALID_OPERATION) && ok;
    subtest(ok, name);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = W;
    config.window_height = H;
    config.window_visual = PIGLIT_GL_VISUAL_RGBA | PIGLIT_GL_VISUAL_DEPTH | PIGLIT_GL_VISUAL_STENCIL;
    config.khr_no_error_support = PIGLIT_HAS_ERRORS;

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
    ou_require_conservative();

    set_up_scene();
    glRenderMode(GL_CONSERVATIVE_OCCLUSION_MESAX);
    const GLint mode = ou_get_integer(GL_RENDER_MODE);
    ou_rect(0, 0, W, H, 0.5f);
    const GLint returned = glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    const bool state_ok = mode == GL_CONSERVATIVE_OCCLUSION_MESAX && returned == 0 &&
                          ou_get_integer(GL_RENDER_MODE) == GL_RENDER;
    if (!state_ok)
        printf("RENDER_MODE %#x inside the mode, RenderMode returned %d\n", mode, returned);
    subtest(state_ok && piglit_check_gl_error(GL_NO_ERROR), "render-mode-state");
    subtest(records_are(0, 1, "RenderMode"), "render-mode-records");

    GLuint pass;
    a.GenOcclusionPasses(1, &pass);
    set_up_scene();
    a.BeginOcclusionPass(GL_CONSERVATIVE_OCCLUSION_MESAX, pass);
    ou_rect(0, 0, W, H, 0.5f);
    a.EndOcclusionPass();
    ScissorsMESAX(0, NULL);
    GLint overflowed = -1;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    const bool pass_ok = records_are(0, 1, "pass object") && overflowed == 0;
    subtest(pass_ok && piglit_check_gl_error(GL_NO_ERROR), "pass-object-records");

    condition_refused(pass, 1, 0.0f, "condition-refuses-count");
    condition_refused(pass, 0, 0.5f, "condition-refuses-ratio");

    clear_colour();
    a.BeginConditionalRenderOcclusionTile(pass, 0, 0, 0.0f, GL_QUERY_WAIT);
    const bool hidden_drawn = red_quad_drawn();
    a.EndConditionalRenderOcclusionTile();
    clear_colour();
    a.BeginConditionalRenderOcclusionTile(pass, 1, 0, 0.0f, GL_QUERY_NO_WAIT);
    const bool visible_drawn = red_quad_drawn();
    a.EndConditionalRenderOcclusionTile();
    if (hidden_drawn || !visible_drawn)
        printf("under the hidden tile %s, under the visible tile %s\n", hidden_drawn ? "drawn" : "not drawn",
               visible_drawn ? "drawn" : "not drawn");
    subtest(!hidden_drawn && visible_drawn && piglit_check_gl_error(GL_NO_ERROR), "condition-decides");

    a.DeleteOcclusionPasses(1, &pass);
    piglit_report_result(result);
}
