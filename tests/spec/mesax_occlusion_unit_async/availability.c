/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: Finish and the order of availability
 * (spec MESAX_occlusion_unit_async, section 5.X.1 and issue 15). After
 * Finish returns, every pass ended before it is available; passes become
 * available in the order in which they ended, so when a pass is available
 * every pass ended before it is too, with one query each and no waiting.
 *
 * Pass A draws 64 window-sized rectangles (much work for the rasterizer),
 * pass B one 4 x 4 rectangle; both over a 256 x 256 window with the depth
 * test off.
 *
 * Subtests:
 *   available-after-finish       A ended, glFinish: one availability query is TRUE
 *   available-in-end-order       A then B ended; once B is available, A is
 *                                (one query), and A's records are A's
 *   finish-writes-no-records     glFinish wrote neither pass's buffers
 *   available-by-polling-alone   A ended, then only availability queries (no
 *                                Flush, no draw): one of them returns TRUE
 *                                (the GL completes an ended pass in finite
 *                                time, issue 15), and the records are A's
 */
#include "ou_util.h"

enum { S = 256, HEAVY = 64 };

static struct ou_async_functions a;
static GLuint records[2][OU_BRIEF_SIZE];

static void
run_pass(GLuint pass, int which)
{
    GLuint *buffers[1] = {records[which]};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    ou_fill(records[which], OU_BRIEF_SIZE);
    OcclusionBuffersMESAX(1, sizes, buffers);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    if (which == 0) {
        for (int i = 0; i < HEAVY; ++i)
            ou_rect(0, 0, S, S, 0.5f);
    } else {
        ou_rect(0, 0, 4, 4, 0.5f);
    }
    a.EndOcclusionPass();
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
    glDisable(GL_DEPTH_TEST);
    GLuint pass[2];
    a.GenOcclusionPasses(2, pass);

    run_pass(pass[0], 0);
    glFinish();
    GLint available = -1;
    a.GetOcclusionPassiv(pass[0], GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX, &available);
    const bool untouched = records[0][OU_NOHC] == OU_SENTINEL && records[0][OU_PHC] == OU_SENTINEL;
    if (available != GL_TRUE)
        printf("after glFinish, availability %d\n", available);
    subtest(available == GL_TRUE && piglit_check_gl_error(GL_NO_ERROR), "available-after-finish");

    run_pass(pass[0], 0);
    run_pass(pass[1], 1);
    const bool b_ready = ou_wait_available(&a, pass[1]);
    available = -1;
    a.GetOcclusionPassiv(pass[0], GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX, &available);
    GLint overflowed = -1;
    a.GetOcclusionPassiv(pass[0], GL_OCCLUSION_PASS_RESULT_NO_WAIT_MESAX, &overflowed);
    const GLuint heavy = HEAVY * S * S;
    const bool a_read = overflowed == 0 && records[0][OU_NOHC] == heavy && records[0][OU_PHC] == heavy;
    if (available != GL_TRUE || !a_read)
        printf("B available: A's availability %d, NO_WAIT read %s (NOHC %u, expected %u)\n", available,
               a_read ? "its records" : "nothing or wrong records", records[0][OU_NOHC], heavy);
    subtest(b_ready && available == GL_TRUE && a_read && piglit_check_gl_error(GL_NO_ERROR),
            "available-in-end-order");

    if (!untouched)
        printf("glFinish wrote the buffers: word 0 0x%08x\n", records[0][OU_NOHC]);
    a.GetOcclusionPassiv(pass[1], GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    subtest(untouched && records[1][OU_NOHC] == 16 && piglit_check_gl_error(GL_NO_ERROR), "finish-writes-no-records");

    run_pass(pass[0], 0);
    const bool polled = ou_wait_available(&a, pass[0]);
    overflowed = -1;
    a.GetOcclusionPassiv(pass[0], GL_OCCLUSION_PASS_RESULT_NO_WAIT_MESAX, &overflowed);
    subtest(polled && overflowed == 0 && records[0][OU_NOHC] == heavy && piglit_check_gl_error(GL_NO_ERROR),
            "available-by-polling-alone");

    a.DeleteOcclusionPasses(2, pass);
    piglit_report_result(result);
}
