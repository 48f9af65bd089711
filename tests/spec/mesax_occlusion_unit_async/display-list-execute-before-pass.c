/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async and display lists compiled with
 * COMPILE_AND_EXECUTE (MESAX_occlusion_unit spec section 5.4 edit): a pass
 * counts the commands issued between the command that begins it and the one
 * that ends it, so a rectangle compiled and executed before
 * BeginOcclusionPassMESAX, executed immediately while the list is compiled,
 * is not counted in the pass, whatever is compiled during the pass (here
 * DepthMask, a state command that is compiled and executed). Depth test
 * off; one default tile, the 32 x 32 window; the rectangle is 8 x 8 and
 * drawn before the pass begins. RenderMode in the same place:
 * display-list-execute-before-pass.c.
 *
 * Subtests:
 *   pass-object-counts-nothing        NOHC 0, PHC 0
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
    const struct ou_async_functions a = ou_init_async();
    glDisable(GL_DEPTH_TEST);
    GLuint *buffers[1] = {record};
    const GLsizei sizes[1] = {OU_BRIEF_SIZE};
    OcclusionBuffersMESAX(1, sizes, buffers);
    const GLuint list = glGenLists(1);
    GLuint pass;
    a.GenOcclusionPasses(1, &pass);

    ou_fill(record, OU_BRIEF_SIZE);
    glNewList(list, GL_COMPILE_AND_EXECUTE);
    ou_rect(0, 0, 8, 8, 0.5f);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    glDepthMask(GL_FALSE);
    a.EndOcclusionPass();
    glEndList();
    GLint overflowed = -1;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    ou_expect_no_fragments(record, "pass-object-counts-nothing", "the rectangle drawn before the pass was counted");

    piglit_report_result(result);
}
