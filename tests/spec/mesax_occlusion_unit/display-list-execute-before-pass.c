/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit and display lists compiled with
 * COMPILE_AND_EXECUTE (spec section 5.4 edit): a pass counts the commands
 * issued between the command that begins it and the one that ends it, so a
 * rectangle compiled and executed before RenderMode(BRIEF_OCCLUSION_MESAX),
 * executed immediately while the list is compiled, is not counted in the
 * pass, whatever is compiled during the pass (here DepthMask, a state
 * command that is compiled and executed).
 * Depth test off; one default tile, the 32 x 32 window; the rectangle is
 * 8 x 8 and drawn before the pass begins. BeginOcclusionPassMESAX in the
 * same place: async-display-list-execute-before-pass.c.
 *
 * Subtests:
 *   render-mode-pass-counts-nothing   NOHC 0, PHC 0
 *   render-mode-again-counts-in-first RenderMode(BRIEF_OCCLUSION_MESAX) again
 *                                     in a pass, right after the rectangle:
 *                                     the first pass NOHC 64, the second 0
 */
#include "ou_util.h"

enum { S = 32 };

static GLuint record[OU_BRIEF_SIZE];

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
    ou_init();
    glDisable(GL_DEPTH_TEST);
    GLuint *buffers[1] = {record};
    const GLsizei sizes[1] = {OU_BRIEF_SIZE};
    OcclusionBuffersMESAX(1, sizes, buffers);
    const GLuint list = glGenLists(1);

    ou_fill(record, OU_BRIEF_SIZE);
    glNewList(list, GL_COMPILE_AND_EXECUTE);
    ou_rect(0, 0, 8, 8, 0.5f);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    glDepthMask(GL_FALSE);
    glRenderMode(GL_RENDER);
    glEndList();
    ou_expect_no_fragments(record, "render-mode-pass-counts-nothing", "the rectangle drawn before the pass was counted");

    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    glNewList(list, GL_COMPILE_AND_EXECUTE);
    ou_rect(0, 0, 8, 8, 0.5f);
    ou_fill(record, OU_BRIEF_SIZE);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);   /* ends the first pass, begins the second */
    const GLuint first_nohc = record[OU_NOHC];
    ou_fill(record, OU_BRIEF_SIZE);
    glDepthMask(GL_FALSE);
    glRenderMode(GL_RENDER);
    glEndList();
    const bool again_ok = first_nohc == 64 && record[OU_NOHC] == 0 && record[OU_PHC] == 0;
    if (!again_ok)
        printf("render-mode-again-counts-in-first: first pass NOHC %u, second NOHC %u PHC %u; expected 64, 0, 0\n",
               first_nohc, record[OU_NOHC], record[OU_PHC]);
    subtest(again_ok && piglit_check_gl_error(GL_NO_ERROR), "render-mode-again-counts-in-first");
    piglit_report_result(result);
}
