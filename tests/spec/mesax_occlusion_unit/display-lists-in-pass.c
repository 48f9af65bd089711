/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit and the drawing commands of display lists (spec
 * section 5.4 edit): during a pass, commands compiled with COMPILE are not
 * executed and count nothing, those compiled with COMPILE_AND_EXECUTE
 * count as they are compiled, and a list called in a pass counts as its
 * commands would; RenderMode is executed immediately, never compiled, so a
 * list neither begins nor ends a pass. Depth test off; one default tile,
 * the 32 x 32 window; the list's rectangle is 8 x 8.
 *
 * Subtests:
 *   compile-in-pass-not-counted              NOHC 0, PHC 0
 *   compile-and-execute-in-pass-counted      NOHC 64, PHC 64
 *   call-list-in-pass-counted                both lists called: NOHC 128
 *   render-mode-executed-not-compiled        RenderMode inside NewList/EndList
 *                                            begins and ends a pass at once (the
 *                                            compiled rectangle not in it); calling
 *                                            the list draws the rectangle in RENDER
 *                                            mode and leaves RENDER mode current
 */
#include "ou_util.h"

enum { S = 32 };

static GLuint record[OU_BRIEF_SIZE];

static void
begin_pass(void)
{
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    ou_fill(record, OU_BRIEF_SIZE);
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
}

static void
expect(const char *name, GLuint nohc, GLuint phc)
{
    const bool ok = record[OU_NOHC] == nohc && record[OU_PHC] == phc;
    if (!ok)
        printf("%s: NOHC %u PHC %u, expected %u %u\n", name, record[OU_NOHC], record[OU_PHC], nohc, phc);
    subtest(ok && piglit_check_gl_error(GL_NO_ERROR), name);
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
    ou_init();
    glDisable(GL_DEPTH_TEST);
    const GLuint lists = glGenLists(3);

    begin_pass();
    glNewList(lists, GL_COMPILE);
    ou_rect(0, 0, 8, 8, 0.5f);
    glEndList();
    glRenderMode(GL_RENDER);
    expect("compile-in-pass-not-counted", 0, 0);

    begin_pass();
    glNewList(lists + 1, GL_COMPILE_AND_EXECUTE);
    ou_rect(8, 8, 16, 16, 0.5f);
    glEndList();
    glRenderMode(GL_RENDER);
    expect("compile-and-execute-in-pass-counted", 64, 64);

    begin_pass();
    glCallList(lists);
    glCallList(lists + 1);
    glRenderMode(GL_RENDER);
    expect("call-list-in-pass-counted", 128, 128);

    /* RenderMode is executed while the list is compiled: the pass begins
     * and ends then, with nothing drawn in it (the rectangle is compiled
     * only); the list holds the rectangle alone. */
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    ou_fill(record, OU_BRIEF_SIZE);
    OcclusionBuffersMESAX(1, sizes, buffers);
    glNewList(lists + 2, GL_COMPILE);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    GLint mode_while_compiling = 0;
    glGetIntegerv(GL_RENDER_MODE, &mode_while_compiling);
    glColor4f(1, 1, 1, 1);
    ou_rect(16, 16, 24, 24, 0.5f);
    const GLint returned = glRenderMode(GL_RENDER);
    glEndList();
    const bool pass_ran = mode_while_compiling == GL_BRIEF_OCCLUSION_MESAX && returned == 0 &&
                          record[OU_NOHC] == 0 && record[OU_PHC] == 0;
    if (!pass_ran)
        printf("while compiling: RENDER_MODE 0x%x, RenderMode returned %d, NOHC %u PHC %u\n", mode_while_compiling,
               returned, record[OU_NOHC], record[OU_PHC]);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    ou_fill(record, OU_BRIEF_SIZE);
    glCallList(lists + 2);
    GLint mode_after_call = 0;
    glGetIntegerv(GL_RENDER_MODE, &mode_after_call);
    static const unsigned char white[4] = {255, 255, 255, 255}, black[4] = {0, 0, 0, 255};
    const bool drawn = ou_probe_rect_rgba_ub(16, 16, 8, 8, white, 0) &&
                       ou_probe_rect_rgba_ub(0, 0, 16, 16, black, 0);
    if (mode_after_call != GL_RENDER || record[OU_NOHC] != OU_SENTINEL)
        printf("after glCallList: RENDER_MODE 0x%x, record word 0 0x%08x\n", mode_after_call, record[OU_NOHC]);
    subtest(pass_ran && drawn && mode_after_call == GL_RENDER && record[OU_NOHC] == OU_SENTINEL &&
                piglit_check_gl_error(GL_NO_ERROR),
            "render-mode-executed-not-compiled");
    piglit_report_result(result);
}
