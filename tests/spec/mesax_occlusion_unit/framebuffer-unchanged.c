/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: in an occlusion mode the framebuffer is never
 * modified (spec issue 11). Colour, depth and stencil are read back before
 * and after a pass in each occlusion mode that draws with every write
 * enabled (blending, stencil REPLACE, depth writes), clears, blits,
 * DrawPixels, CopyPixels and Bitmap; they must be bit-identical, and the
 * pass must have counted fragments (so the draws did reach the unit).
 */
#include <stdlib.h>

#include "ou_util.h"

#define W 48
#define H 40

static PFNGLBLITFRAMEBUFFERPROC BlitFramebuffer;
static PFNGLCLEARBUFFERFVPROC ClearBufferfv;

static void
read_all(GLubyte *color, GLuint *depth, GLubyte *stencil)
{
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, color);
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, depth);
    glReadPixels(0, 0, W, H, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil);
}

/* Something non-trivial in all three buffers. */
static void
paint_scene(void)
{
    glClearColor(0.2f, 0.4f, 0.6f, 0.8f);
    glClearDepth(0.75);
    glClearStencil(3);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 7, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glColor4f(1, 0, 0, 1);
    ou_rect(5, 5, 25, 30, 0.5f);
    glColor4f(0, 1, 0, 1);
    ou_rect(15, 10, 40, 35, 0.25f);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_DEPTH_TEST);
}

/* Everything that writes the framebuffer in GL_RENDER. */
static void
write_everything(void)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 200, 0xff);
    glStencilOp(GL_REPLACE, GL_REPLACE, GL_REPLACE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glColor4f(0.5f, 0.5f, 0.5f, 0.5f);
    ou_rect(0, 0, W, H, 0.1f);
    glBegin(GL_LINES);
    glVertex3f(0.5f, 0.5f, 0.9f);
    glVertex3f(W - 0.5f, H - 0.5f, 0.9f);
    glEnd();
    glPointSize(3);
    glBegin(GL_POINTS);
    glVertex3f(20.5f, 20.5f, 0.05f);
    glEnd();
    glDisable(GL_BLEND);

    glClearColor(1, 1, 1, 1);
    glClearDepth(0.0);
    glClearStencil(255);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    const GLfloat white[4] = {1, 1, 1, 1};
    ClearBufferfv(GL_COLOR, 0, white);

    static GLubyte pixels[8 * 8 * 4];
    memset(pixels, 0x7f, sizeof(pixels));
    glRasterPos3f(2, 2, 0.2f);
    glDrawPixels(8, 8, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    glRasterPos3f(30, 2, 0.2f);
    glCopyPixels(0, 0, 8, 8, GL_COLOR);
    static const GLubyte bitmap[8] = {0xff, 0x81, 0x81, 0x81, 0x81, 0x81, 0x81, 0xff};
    glRasterPos3f(10, 30, 0.2f);
    glBitmap(8, 8, 0, 0, 0, 0, bitmap);

    BlitFramebuffer(0, 0, 16, 16, 30, 20, 46, 36, GL_COLOR_BUFFER_BIT, GL_NEAREST);

    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
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
    ou_init();
    BlitFramebuffer = glBlitFramebuffer;
    ClearBufferfv = glClearBufferfv;
    if (!BlitFramebuffer || !ClearBufferfv) {
        printf("needs glBlitFramebuffer and glClearBufferfv (GL 3.0)\n");
        piglit_report_result(PIGLIT_SKIP);
    }
    enum piglit_result result = PIGLIT_PASS;
    const size_t n = (size_t)W * H;
    GLubyte *color0 = malloc(n * 4), *color1 = malloc(n * 4), *stencil0 = malloc(n), *stencil1 = malloc(n);
    GLuint *depth0 = malloc(n * 4), *depth1 = malloc(n * 4);

    paint_scene();
    read_all(color0, depth0, stencil0);

    const GLenum modes[2] = {GL_BRIEF_OCCLUSION_MESAX, GL_VERBOSE_OCCLUSION_MESAX};
    const char *names[2] = {"brief", "verbose"};
    for (int m = 0; m < 2; ++m) {
        static GLuint record[64];
        GLuint *buffers[1] = {record};
        GLsizei sizes[1] = {64};
        ou_fill(record, 64);
        OcclusionBuffersMESAX(1, sizes, buffers);
        glRenderMode(modes[m]);
        write_everything();
        glRenderMode(GL_RENDER);
        read_all(color1, depth1, stencil1);

        bool same_color = memcmp(color0, color1, n * 4) == 0;
        bool same_depth = memcmp(depth0, depth1, n * 4) == 0;
        bool same_stencil = memcmp(stencil0, stencil1, n) == 0;
        bool counted = record[OU_PHC] >= (GLuint)n;   /* at least the full-screen rectangle */
        bool ok = same_color && same_depth && same_stencil && counted && piglit_check_gl_error(GL_NO_ERROR);
        if (!ok)
            printf("%s: colour %s, depth %s, stencil %s, PHC %u\n", names[m], same_color ? "same" : "CHANGED",
                   same_depth ? "same" : "CHANGED", same_stencil ? "same" : "CHANGED", record[OU_PHC]);
        piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "%s-pass-writes-nothing", names[m]);
        if (!ok)
            result = PIGLIT_FAIL;
    }

    /* The same commands in GL_RENDER do change all three: the test can fail. */
    write_everything();
    read_all(color1, depth1, stencil1);
    bool changes = memcmp(color0, color1, n * 4) && memcmp(depth0, depth1, n * 4) && memcmp(stencil0, stencil1, n);
    piglit_report_subtest_result(changes ? PIGLIT_PASS : PIGLIT_FAIL, "render-mode-writes-everything");
    if (!changes)
        result = PIGLIT_FAIL;

    free(color0); free(color1); free(stencil0); free(stencil1); free(depth0); free(depth1);
    piglit_report_result(result);
}
