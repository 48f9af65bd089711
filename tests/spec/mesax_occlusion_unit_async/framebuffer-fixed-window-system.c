/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: a pass object follows the occlusion mode's
 * rules between BeginOcclusionPassMESAX and EndOcclusionPassMESAX (issue 1 of
 * the async spec: "the framebuffer is fixed"), a window-system-provided
 * framebuffer's too (MESAX_occlusion_unit, issue 24). An async pass begun on
 * a 64 x 64 buffer with tiles (0, 0, 32, 32) and (32, 32, 32, 32) draws an
 * 8 x 8 quad at (40, 40) on the window system's framebuffer 0 (not piglit's
 * FBO); MakeCurrent then moves the context to a buffer of 32 x 32
 * (ou_make_current_on_new_buffer), which the GL cannot refuse. From then on the pass's drawing
 * commands generate INVALID_OPERATION and draw nothing: on the smaller buffer
 * a quad at (4, 4) would otherwise be credited to tile 0 with the old
 * buffer's y-flip. The pass ends as ever and its result counts what it drew
 * before the change. Depth tests are off: every fragment passes.
 *
 * Subtests:
 *   make-current-smaller-no-error      MakeCurrent itself succeeds, no GL error
 *   draw-after-change-invalid-operation  the quad at (4, 4): INVALID_OPERATION
 *   rejected-draw-draws-nothing        a SAMPLES_PASSED query around it reads 0
 *   result-counts-before-change        OCCLUSION_PASS_RESULT_MESAX 0, no error; NOHC 0
 *                                      for tile 0 and 64 for tile 1, x and y 40..47
 */
#include "ou_util.h"

#include "ou_two_contexts.h"

enum { SMALL = 32, LARGE = 64 };

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = LARGE;
    config.window_height = LARGE;
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
    const struct ou_async_functions a = ou_init_async();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);   /* the window system's, not piglit_winsys_fbo */
    glDisable(GL_DEPTH_TEST);
    PFNGLGENQUERIESPROC GenQueries = glGenQueries;
    PFNGLBEGINQUERYPROC BeginQuery = glBeginQuery;
    PFNGLENDQUERYPROC EndQuery = glEndQuery;
    PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv =
        glGetQueryObjectuiv;
    GLuint query, pass;
    GenQueries(1, &query);
    a.GenOcclusionPasses(1, &pass);

    GLuint records[2][OU_BRIEF_SIZE];
    GLuint *buffers[2] = {records[0], records[1]};
    GLsizei sizes[2] = {OU_BRIEF_SIZE, OU_BRIEF_SIZE};
    const GLint tiles[8] = {0, 0, SMALL, SMALL, SMALL, SMALL, SMALL, SMALL};
    ou_fill(records[0], OU_BRIEF_SIZE);
    ou_fill(records[1], OU_BRIEF_SIZE);
    ScissorsMESAX(2, tiles);
    OcclusionBuffersMESAX(2, sizes, buffers);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    ou_rect(40, 40, 48, 48, 0.5f);

    const bool made = ou_make_current_on_new_buffer(SMALL);
    GLenum e = ou_first_error();
    if (!made || e != GL_NO_ERROR)
        printf("MakeCurrent on 32 x 32 in an async pass: %s, error 0x%x\n", made ? "made" : "failed", e);
    subtest(made && e == GL_NO_ERROR, "make-current-smaller-no-error");
    glViewport(0, 0, SMALL, SMALL);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, SMALL, 0, SMALL, 0, -1);
    glMatrixMode(GL_MODELVIEW);

    BeginQuery(GL_SAMPLES_PASSED, query);
    ou_rect(4, 4, 12, 12, 0.5f);
    e = ou_first_error();
    EndQuery(GL_SAMPLES_PASSED);
    if (e != GL_INVALID_OPERATION)
        printf("a quad inside tile 0 after the change: error 0x%x (expected INVALID_OPERATION)\n", e);
    subtest(e == GL_INVALID_OPERATION, "draw-after-change-invalid-operation");

    GLuint samples = 0xdeadbeef;
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    if (samples != 0)
        printf("SAMPLES_PASSED around the draw after the change: %u (expected 0)\n", samples);
    subtest(samples == 0, "rejected-draw-draws-nothing");

    a.EndOcclusionPass();
    GLint overflowed = -1;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    e = ou_first_error();
    const GLuint *r = records[1];
    const bool counted = records[0][OU_NOHC] == 0 && r[OU_NOHC] == 64 && r[OU_XMIN] == 40 &&
                         r[OU_XMAX] == 47 && r[OU_YMIN] == 40 && r[OU_YMAX] == 47;
    if (!counted || overflowed != 0 || e != GL_NO_ERROR)
        printf("the pass: NOHC %u and %u, tile 1 x %u..%u y %u..%u (expected 0 and 64, 40..47, 40..47); "
               "result %d, error 0x%x\n",
               records[0][OU_NOHC], r[OU_NOHC], r[OU_XMIN], r[OU_XMAX], r[OU_YMIN], r[OU_YMAX], overflowed, e);
    subtest(counted && overflowed == 0 && e == GL_NO_ERROR, "result-counts-before-change");
    a.DeleteOcclusionPasses(1, &pass);
    piglit_report_result(result);
}
