/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: a pass entered right after a framebuffer object
 * is bound, or after its renderbuffers are reallocated, takes its tiles
 * against that framebuffer as it now is (section 5.X: a tile holds the
 * fragments of the draw framebuffer current when the pass begins), not
 * against the size the GL knew at its last draw. Nothing is drawn or
 * cleared between the change and the pass, which is where the GL has not
 * yet validated the new framebuffer.
 *
 * Subtests:
 *   new-fbo-first-pass-counts-whole
 *       a window of 32 x 32, then a new 64 x 64 FBO bound and a pass with
 *       one tile over 64 x 64: a quad over all of it counts 4096.
 *   reallocated-fbo-first-pass-counts-whole
 *       the same FBO's renderbuffers reallocated to 128 x 128, then a pass
 *       with a tile over 128 x 128: 16384.
 *   default-tile-follows-new-viewport
 *       no tiles (the viewport is the tile): after binding a fresh 48 x 48
 *       FBO and setting the viewport to it, 2304.
 */
#include "ou_util.h"

static struct ou_fbo_functions f;
static GLuint colour, depth;

static void
storage(int size)
{
    f.BindRenderbuffer(GL_RENDERBUFFER, colour);
    f.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, size, size);
    f.BindRenderbuffer(GL_RENDERBUFFER, depth);
    f.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, size, size);
}

/* Not ou_make_fbo: checking completeness would validate the framebuffer,
 * which is what a pass right after binding must do by itself. */
static GLuint
make_fbo(int size)
{
    GLuint fbo;
    f.GenFramebuffers(1, &fbo);
    f.GenRenderbuffers(1, &colour);
    f.GenRenderbuffers(1, &depth);
    storage(size);
    f.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    f.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
    f.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    return fbo;
}

/* NOHC of one pass drawing a quad over size x size, with one tile over it
 * (or the default tile when `tiled` is false). */
static GLuint
pass_over(int size, bool tiled)
{
    GLuint record[8];
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {8};
    const GLint tile[4] = {0, 0, size, size};
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, size, 0, size, 0, -1);
    glMatrixMode(GL_MODELVIEW);
    OcclusionBuffersMESAX(1, sizes, buffers);
    ScissorsMESAX(tiled ? 1 : 0, tiled ? tile : NULL);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    ou_rect(0, 0, (float)size, (float)size, 0.5f);
    glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    return record[OU_NOHC];
}

static bool
expect(const char *name, GLuint nohc, GLuint expected)
{
    if (nohc != expected)
        printf("%s: NOHC %u, expected %u\n", name, nohc, expected);
    subtest(nohc == expected && piglit_check_gl_error(GL_NO_ERROR), name);
    return nohc == expected;
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = 32;
    config.window_height = 32;
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
    f = ou_fbo_functions();
    glDisable(GL_DEPTH_TEST);

    /* The window, drawn once, so that the GL has validated a 32 x 32 framebuffer. */
    ou_rect(0, 0, 32, 32, 0.5f);
    glFinish();

    make_fbo(64);
    glViewport(0, 0, 64, 64);
    expect("new-fbo-first-pass-counts-whole", pass_over(64, true), 64 * 64);

    storage(128);
    glViewport(0, 0, 128, 128);
    expect("reallocated-fbo-first-pass-counts-whole", pass_over(128, true), 128 * 128);

    f.BindFramebuffer(GL_FRAMEBUFFER, piglit_winsys_fbo);
    ou_rect(0, 0, 32, 32, 0.5f);
    glFinish();
    make_fbo(48);
    glViewport(0, 0, 48, 48);
    expect("default-tile-follows-new-viewport", pass_over(48, false), 48 * 48);

    piglit_report_result(result);
}
