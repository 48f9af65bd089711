/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: a pass deleted, or begun again, right
 * after it ended (nothing read, no Flush) is discarded without waiting
 * forever (spec MESAX_occlusion_unit_async, section 5.X.1: Delete discards
 * the pass's records; Begin on the name makes the object hold the new
 * pass and no earlier one). An implementation that submits an ended pass
 * only when its results are needed must submit it, or wait for nothing,
 * before it frees it. The test fails by timing out (alarm, 30 s) if either
 * command hangs.
 *
 * 64 x 64 window, depth test off; each pass draws a quad over the window
 * (PHC = NOHC = 4096).
 *
 * Subtests:
 *   delete-after-end            End, then Delete: returns; the name is gone
 *   begin-again-after-end       End, then Begin on the same name with a
 *                               quad of 16 x 16: the new pass's records,
 *                               not the old one's (NOHC 256)
 *   draws-after-delete-count    a pass after the deleted one, with a draw
 *                               between, counts its own quad (NOHC 4096)
 */
#define _DEFAULT_SOURCE 1   /* alarm */
#include <unistd.h>

#include "ou_util.h"

enum { S = 64 };

static struct ou_async_functions a;
static GLuint record[OU_BRIEF_SIZE];

static void
pass_over(GLuint pass, float size)
{
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    ou_fill(record, OU_BRIEF_SIZE);
    OcclusionBuffersMESAX(1, sizes, buffers);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    ou_rect(0, 0, size, size, 0.5f);
    a.EndOcclusionPass();
}

static bool
counts(GLuint pass, GLuint want, const char *name)
{
    GLint overflowed = -1;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    if (overflowed != 0 || record[OU_NOHC] != want || record[OU_PHC] != want) {
        printf("%s: NOHC %u PHC %u overflowed %d, expected %u, %u, 0\n", name, record[OU_NOHC], record[OU_PHC],
               overflowed, want, want);
        return false;
    }
    return true;
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
    alarm(30);
    a = ou_init_async();
    glDisable(GL_DEPTH_TEST);

    GLuint pass[2];
    a.GenOcclusionPasses(2, pass);
    pass_over(pass[0], S);
    a.DeleteOcclusionPasses(1, &pass[0]);
    subtest(!a.IsOcclusionPass(pass[0]) && piglit_check_gl_error(GL_NO_ERROR), "delete-after-end");

    pass_over(pass[1], S);
    pass_over(pass[1], 16);
    subtest(counts(pass[1], 256, "begin-again") && piglit_check_gl_error(GL_NO_ERROR), "begin-again-after-end");

    a.GenOcclusionPasses(1, &pass[0]);
    pass_over(pass[0], S);
    a.DeleteOcclusionPasses(1, &pass[0]);
    ou_rect(0, 0, S, S, 0.5f);
    a.GenOcclusionPasses(1, &pass[0]);
    pass_over(pass[0], S);
    subtest(counts(pass[0], S * S, "after delete") && piglit_check_gl_error(GL_NO_ERROR), "draws-after-delete-count");

    a.DeleteOcclusionPasses(2, pass);
    piglit_report_result(result);
}
