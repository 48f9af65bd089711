/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: the bounding box and depth range of a tile equal
 * those of the pixels whose depth a GL_RENDER draw of the same geometry
 * changes, read back with glReadPixels. The geometry is a tilted triangle,
 * partly behind an occluder, so z varies over it.
 *
 * Subtests:
 *   tilted-triangle-partly-occluded
 *       the window's 24-bit depth buffer. Box exact; zmin and zmax within
 *       OU_Z24_READBACK_TOLERANCE (ou_util.h derives it from the buffer's
 *       quantization) of the depth read back as GL_UNSIGNED_INT.
 *   tilted-triangle-float-depth-buffer
 *       a framebuffer object with a DEPTH_COMPONENT32F buffer, which stores
 *       each fragment's z as the depth test used it, unconverted. The record
 *       maps that same z (section 5.X), so zmin and zmax equal ou_depth() of
 *       the read-back minimum and maximum exactly; a record of a quantized
 *       depth would not.
 */
#include "ou_util.h"

#define W 64
#define H 48

static void
draw_target(void)
{
    glBegin(GL_TRIANGLES);
    glVertex3f(4.4f, 3.1f, 0.1f);
    glVertex3f(59.7f, 9.3f, 0.9f);
    glVertex3f(30.2f, 44.6f, 0.55f);
    glEnd();
}

static void
setup_scene(void)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    ou_rect(30, 0, 64, 48, 0.5f);
}

/* Box and depth range of the pixels the target changes in GL_RENDER, then
 * the record of a brief pass over the same scene against them; `float_depth`
 * reads the depth as GL_FLOAT, else as GL_UNSIGNED_INT. */
static bool
record_matches_render(const char *name, bool float_depth, GLuint z_tolerance)
{
    static GLuint before[W * H], after[W * H];
    static GLfloat depth[W * H];

    setup_scene();
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, before);
    draw_target();
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, after);
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    GLuint n = 0, xmin = OU_EMPTY_MIN, xmax = 0, ymin = OU_EMPTY_MIN, ymax = 0;
    GLuint zmin = OU_EMPTY_MIN, zmax = 0;
    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            const int i = y * W + x;
            if (before[i] == after[i])
                continue;
            const GLuint z = float_depth ? ou_depth(depth[i]) : after[i];
            ++n;
            xmin = (GLuint)x < xmin ? (GLuint)x : xmin;
            xmax = (GLuint)x > xmax ? (GLuint)x : xmax;
            ymin = (GLuint)y < ymin ? (GLuint)y : ymin;
            ymax = (GLuint)y > ymax ? (GLuint)y : ymax;
            zmin = z < zmin ? z : zmin;
            zmax = z > zmax ? z : zmax;
        }
    }

    GLuint rec[1][OU_BRIEF_SIZE];
    setup_scene();
    ou_brief_pass(0, NULL, rec, draw_target);
    const GLuint expected[OU_BRIEF_SIZE] = {n, rec[0][OU_PHC], xmin, xmax, ymin, ymax, zmin, zmax};
    if (n <= 100 || rec[0][OU_PHC] <= n)
        printf("%s: %u pixels changed, PHC %u: the scene is not partly occluded\n", name, n, rec[0][OU_PHC]);
    return n > 100 && rec[0][OU_PHC] > n && ou_check_record(name, rec[0], expected, z_tolerance) &&
           piglit_check_gl_error(GL_NO_ERROR);
}

/* Binds a W x H framebuffer object with RGBA8 colour and 32-bit float depth. */
static bool
bind_float_depth_fbo(void)
{
    if (!piglit_is_extension_supported("GL_ARB_framebuffer_object") ||
        !piglit_is_extension_supported("GL_ARB_depth_buffer_float"))
        return false;
    PFNGLGENFRAMEBUFFERSPROC GenFramebuffers = glGenFramebuffers;
    PFNGLBINDFRAMEBUFFERPROC BindFramebuffer = glBindFramebuffer;
    PFNGLGENRENDERBUFFERSPROC GenRenderbuffers =
        glGenRenderbuffers;
    PFNGLBINDRENDERBUFFERPROC BindRenderbuffer =
        glBindRenderbuffer;
    PFNGLRENDERBUFFERSTORAGEPROC RenderbufferStorage =
        glRenderbufferStorage;
    PFNGLFRAMEBUFFERRENDERBUFFERPROC FramebufferRenderbuffer =
        glFramebufferRenderbuffer;
    PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus =
        glCheckFramebufferStatus;
    GLuint fbo, rb[2];
    GenFramebuffers(1, &fbo);
    GenRenderbuffers(2, rb);
    BindFramebuffer(GL_FRAMEBUFFER, fbo);
    BindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, W, H);
    BindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, W, H);
    FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    const GLenum status = CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        printf("the float depth framebuffer is incomplete (0x%04x)\n", status);
    return status == GL_FRAMEBUFFER_COMPLETE && piglit_check_gl_error(GL_NO_ERROR);
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

    subtest(record_matches_render("24-bit depth", false, OU_Z24_READBACK_TOLERANCE), "tilted-triangle-partly-occluded");

    if (bind_float_depth_fbo())
        subtest(record_matches_render("float depth", true, 0), "tilted-triangle-float-depth-buffer");
    else
        ou_subtest_unsupported("tilted-triangle-float-depth-buffer", "a complete DEPTH_COMPONENT32F framebuffer");

    piglit_report_result(result);
}
