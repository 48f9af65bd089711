/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: the framebuffer of an occlusion pass is fixed for
 * the pass, a window-system-provided one too (Dependencies on framebuffer
 * objects and Errors; issue 24). MakeCurrent of a larger buffer in the middle
 * of a pass (ou_make_current_on_new_buffer of 64 x 64 for a pass begun on
 * 32 x 32: OSMesa's, or EGL's on a pbuffer inside piglit; the pass is on the
 * window system's framebuffer 0, not on piglit's FBO) changes the
 * framebuffer under the pass, which the GL cannot refuse: from
 * then on the pass's drawing commands generate INVALID_OPERATION and draw
 * nothing, so no fragment is counted against tiles set for the old buffer
 * (the old y-flip would credit a quad at the new buffer's top to tile 0, and
 * miss one inside it). The pass ends as ever and counts what it drew before.
 * Depth tests are off: every fragment passes.
 *
 * Subtests:
 *   make-current-larger-no-error       MakeCurrent itself succeeds, no GL error
 *   begin-after-change-invalid-operation  an 8 x 8 quad inside tile 0 (Begin/End)
 *   draw-arrays-after-change-invalid-operation  an 8 x 8 quad at (40, 40), outside
 *                                      tile 0, with DrawArrays
 *   pixels-after-change-invalid-operation  DrawPixels, Bitmap and CopyPixels
 *   rejected-draws-draw-nothing        a SAMPLES_PASSED query around all of them reads 0
 *   pass-counts-before-change          RenderMode(RENDER) returns 0, no error; tile 0's
 *                                      record is the quad drawn before the change:
 *                                      NOHC 64, x 4..11, y 4..11
 *   next-pass-on-new-buffer            a pass begun on the 64 x 64 buffer with tiles
 *                                      (0, 0, 32, 32) and (32, 32, 32, 32) counts a quad
 *                                      at (40, 40) in tile 1 only: 0 and 64
 */
#include "ou_util.h"

#include "ou_two_contexts.h"

enum { SMALL = 32, LARGE = 64 };

static void
pixel_projection(int size)
{
    glViewport(0, 0, size, size);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, size, 0, size, 0, -1);
    glMatrixMode(GL_MODELVIEW);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = SMALL;
    config.window_height = SMALL;
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
    ou_init();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);   /* the window system's, not piglit_winsys_fbo */
    glDisable(GL_DEPTH_TEST);
    PFNGLGENQUERIESPROC GenQueries = glGenQueries;
    PFNGLBEGINQUERYPROC BeginQuery = glBeginQuery;
    PFNGLENDQUERYPROC EndQuery = glEndQuery;
    PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv =
        glGetQueryObjectuiv;
    GLuint query;
    GenQueries(1, &query);

    GLuint records[2][OU_BRIEF_SIZE];
    GLuint *buffers[2] = {records[0], records[1]};
    GLsizei sizes[2] = {OU_BRIEF_SIZE, OU_BRIEF_SIZE};
    const GLint tiles[8] = {0, 0, SMALL, SMALL, SMALL, SMALL, SMALL, SMALL};
    ou_fill(records[0], OU_BRIEF_SIZE);
    ScissorsMESAX(1, tiles);
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    ou_rect(4, 4, 12, 12, 0.5f);

    /* The context's window-system framebuffer becomes 64 x 64. */
    const bool made = ou_make_current_on_new_buffer(LARGE);
    subtest(made && ou_first_error() == GL_NO_ERROR, "make-current-larger-no-error");
    pixel_projection(LARGE);

    BeginQuery(GL_SAMPLES_PASSED, query);
    ou_rect(4, 4, 12, 12, 0.5f);
    GLenum e = ou_first_error();
    if (e != GL_INVALID_OPERATION)
        printf("a quad inside tile 0 after the change: error 0x%x (expected INVALID_OPERATION)\n", e);
    subtest(e == GL_INVALID_OPERATION, "begin-after-change-invalid-operation");

    static const GLfloat corners[4][3] = {{40, 40, 0.5f}, {48, 40, 0.5f}, {48, 48, 0.5f}, {40, 48, 0.5f}};
    glVertexPointer(3, GL_FLOAT, 0, corners);
    glEnableClientState(GL_VERTEX_ARRAY);
    glDrawArrays(GL_QUADS, 0, 4);
    glDisableClientState(GL_VERTEX_ARRAY);
    e = ou_first_error();
    if (e != GL_INVALID_OPERATION)
        printf("a DrawArrays quad at (40, 40) after the change: error 0x%x (expected INVALID_OPERATION)\n", e);
    subtest(e == GL_INVALID_OPERATION, "draw-arrays-after-change-invalid-operation");

    static GLubyte pixels[8 * 8 * 4], bitmap[8 * 8 / 8];
    memset(bitmap, 0xff, sizeof(bitmap));
    glRasterPos2i(4, 4);
    glDrawPixels(8, 8, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    const GLenum draw_pixels = ou_first_error();
    glBitmap(8, 8, 0, 0, 0, 0, bitmap);
    const GLenum bitmap_error = ou_first_error();
    glCopyPixels(0, 0, 8, 8, GL_COLOR);
    const GLenum copy_pixels = ou_first_error();
    EndQuery(GL_SAMPLES_PASSED);
    if (draw_pixels != GL_INVALID_OPERATION || bitmap_error != GL_INVALID_OPERATION ||
        copy_pixels != GL_INVALID_OPERATION)
        printf("after the change: DrawPixels error 0x%x, Bitmap 0x%x, CopyPixels 0x%x (expected 0x%x)\n",
               draw_pixels, bitmap_error, copy_pixels, GL_INVALID_OPERATION);
    subtest(draw_pixels == GL_INVALID_OPERATION && bitmap_error == GL_INVALID_OPERATION &&
                copy_pixels == GL_INVALID_OPERATION,
            "pixels-after-change-invalid-operation");

    GLuint samples = 0xdeadbeef;
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    if (samples != 0)
        printf("SAMPLES_PASSED around the draws after the change: %u (expected 0)\n", samples);
    subtest(samples == 0, "rejected-draws-draw-nothing");

    const GLint overflowed = glRenderMode(GL_RENDER);
    e = ou_first_error();
    const GLuint *r = records[0];
    const bool counted = r[OU_NOHC] == 64 && r[OU_XMIN] == 4 && r[OU_XMAX] == 11 && r[OU_YMIN] == 4 &&
                         r[OU_YMAX] == 11;
    if (!counted || overflowed != 0 || e != GL_NO_ERROR)
        printf("tile 0: NOHC %u x %u..%u y %u..%u (expected 64, 4..11, 4..11); RenderMode %d, error 0x%x\n",
               r[OU_NOHC], r[OU_XMIN], r[OU_XMAX], r[OU_YMIN], r[OU_YMAX], overflowed, e);
    subtest(counted && overflowed == 0 && e == GL_NO_ERROR, "pass-counts-before-change");

    /* A pass begun on the new buffer has it as its framebuffer. */
    ou_fill(records[0], OU_BRIEF_SIZE);
    ou_fill(records[1], OU_BRIEF_SIZE);
    ScissorsMESAX(2, tiles);
    OcclusionBuffersMESAX(2, sizes, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    ou_rect(40, 40, 48, 48, 0.5f);
    glRenderMode(GL_RENDER);
    e = ou_first_error();
    if (records[0][OU_NOHC] != 0 || records[1][OU_NOHC] != 64 || e != GL_NO_ERROR)
        printf("a pass on the 64 x 64 buffer: NOHC %u and %u (expected 0 and 64), error 0x%x\n", records[0][OU_NOHC],
               records[1][OU_NOHC], e);
    subtest(records[0][OU_NOHC] == 0 && records[1][OU_NOHC] == 64 && e == GL_NO_ERROR, "next-pass-on-new-buffer");
    piglit_report_result(result);
}
