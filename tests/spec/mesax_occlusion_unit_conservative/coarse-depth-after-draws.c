/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit(_conservative) on llvmpipe: a draw that writes
 * depth between two passes of one scene makes the coarse depth the first
 * pass read stale, and the second pass must see the depth the draw left
 * (spec MESAX_occlusion_unit_async, issue 2: a pass's fragments are tested
 * against the depth buffer as every command issued before its Begin left
 * it). llvmpipe reads each 16x16 block's depth bounds when a pass first
 * needs them and keeps them in the bin while no draw writes the block;
 * bounds kept past a draw that wrote the block would reject fragments that
 * pass.
 *
 * A 128 x 128 window (2 x 2 bins), depth cleared to 0.5. Pass 1 (depth
 * function LESS, a quad at 0.75 over the window: hidden) reads every
 * block's bounds. Then, in GL_RENDER and the same scene (nothing is read
 * in between), a draw writes depth, and pass 2 tests a quad over the
 * window. The passes are pass objects read at the end, so all of it is
 * one scene on llvmpipe.
 *
 * Subtests, each in brief mode (NOHC must be the analytic count) and in
 * conservative mode (the tile's answer must be 1):
 *   nearer-draw-then-greater   the draw writes 0.25 (LESS) over columns
 *                              [0, W1); pass 2 tests 0.4 with GREATER: the
 *                              W1 x 128 pixels there pass, none elsewhere
 *                              (stale bounds, least 0.5, would reject all)
 *   farther-draw-then-less     the draw writes 0.75 (GREATER) over columns
 *                              [0, W1); pass 2 tests 0.6 with LESS
 * with W1 = 64 (whole bins: llvmpipe shades them whole) and W1 = 40 (a
 * draw ending inside a 16x16 block).
 */
#include "ou_util.h"

enum { W = 128, H = 128 };

static struct ou_async_functions a;

static void
draw_quad(float x1, float z)
{
    ou_rect(0, 0, x1, H, z);
}

/* Pass 1, the draw, pass 2; returns pass 2's record word 0. */
static GLuint
run(GLenum mode, GLenum draw_func, float draw_z, int w1, GLenum test_func, float test_z)
{
    static GLuint records[2][OU_BRIEF_SIZE];
    GLuint passes[2];
    a.GenOcclusionPasses(2, passes);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClearDepth(0.5);
    glClear(GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT);

    for (int p = 0; p < 2; ++p) {
        GLuint *buffers[1] = {records[p]};
        GLsizei sizes[1] = {OU_BRIEF_SIZE};
        ou_fill(records[p], OU_BRIEF_SIZE);
        OcclusionBuffersMESAX(1, sizes, buffers);
        ScissorsMESAX(0, NULL);
        if (p == 1) {
            /* The draw between the passes, depth written. */
            glDepthFunc(draw_func);
            draw_quad((float)w1, draw_z);
        }
        glDepthFunc(p == 0 ? GL_LESS : test_func);
        a.BeginOcclusionPass(mode, passes[p]);
        draw_quad(W, p == 0 ? 0.75f : test_z);
        a.EndOcclusionPass();
    }
    GLint overflowed;
    for (int p = 0; p < 2; ++p)
        a.GetOcclusionPassiv(passes[p], GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    a.DeleteOcclusionPasses(2, passes);
    glDepthFunc(GL_LESS);
    if (records[0][0] != 0)
        printf("pass 1 over the cleared depth counted %u, expected 0\n", records[0][0]);
    return records[0][0] == 0 ? records[1][0] : 0xffffffffu;
}

static void
check(const char *name, GLenum draw_func, float draw_z, GLenum test_func, float test_z)
{
    static const int widths[2] = {64, 40};
    bool ok = true;
    for (int i = 0; i < 2; ++i) {
        const int w1 = widths[i];
        const GLuint brief = run(GL_BRIEF_OCCLUSION_MESAX, draw_func, draw_z, w1, test_func, test_z);
        const GLuint expected = (GLuint)(w1 * H);
        if (brief != expected) {
            printf("%s, draw over %d columns: brief NOHC %u, expected %u\n", name, w1, brief, expected);
            ok = false;
        }
        const GLuint conservative = run(GL_CONSERVATIVE_OCCLUSION_MESAX, draw_func, draw_z, w1, test_func, test_z);
        if (conservative != 1) {
            printf("%s, draw over %d columns: conservative answer %u, expected 1\n", name, w1, conservative);
            ok = false;
        }
    }
    subtest(ok && piglit_check_gl_error(GL_NO_ERROR), name);
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
    a = ou_init_async();
    ou_require_conservative();
    check("nearer-draw-then-greater", GL_LESS, 0.25f, GL_GREATER, 0.4f);
    check("farther-draw-then-less", GL_GREATER, 0.75f, GL_LESS, 0.6f);
    piglit_report_result(result);
}
