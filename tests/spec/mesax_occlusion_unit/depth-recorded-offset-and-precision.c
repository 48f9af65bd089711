/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: the recorded depth is the depth the depth test
 * uses, after polygon offset and before conversion to the depth buffer's
 * format (section 5.X, issue 3), with a 24-bit and with a 16-bit depth
 * buffer.
 *
 * A quad at window z 0.3 (ou_init's projection), S x S pixels. Polygon
 * offset units u move depth by u * r, r the buffer's minimum resolvable
 * difference, which GL leaves to the implementation within a small factor
 * of 2^-bits: the tests accept 0.5 to 2 times 2^-bits per unit.
 *
 * Subtests, each on the window's 24-bit buffer and on a framebuffer object
 * with a DEPTH_COMPONENT16 buffer:
 *   offset-recorded-{24,16}-bit   units -4: the record's z is below the
 *                                 record without offset by 4 r, and the depth
 *                                 test (LESS, against the quad drawn without
 *                                 offset) passes every fragment; units +4: the
 *                                 record is above by 4 r and the test passes
 *                                 none
 *   not-quantized-16-bit          without offset the record is z 0.3 to
 *                                 float precision, not the 16-bit buffer's
 *                                 value of it, which the read-back shows is
 *                                 farther from 0.3 than the record is
 */
#include "ou_util.h"

#include <math.h>

#define S 16

static const double z_quad = 0.3;

static void
quad(void)
{
    ou_rect(0, 0, S, S, (float)z_quad);
}

/* A pass over the quad with offset units `units` (0: no offset) under
 * depth function `func`, against the quad drawn without offset; returns
 * the record. */
static void
offset_pass(GLenum func, float units, GLuint record[OU_BRIEF_SIZE])
{
    GLuint records[1][OU_BRIEF_SIZE];
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glClear(GL_DEPTH_BUFFER_BIT);
    quad();   /* the buffer holds the quad's own depth */
    glDepthFunc(func);
    if (units != 0) {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(0, units);
    }
    ou_brief_pass(0, NULL, records, quad);
    glDisable(GL_POLYGON_OFFSET_FILL);
    memcpy(record, records[0], sizeof(records[0]));
}

static void
check_offset(const char *name, int bits)
{
    GLuint none[OU_BRIEF_SIZE], nearer[OU_BRIEF_SIZE], farther[OU_BRIEF_SIZE];
    GLuint nearer_less[OU_BRIEF_SIZE], farther_less[OU_BRIEF_SIZE];
    offset_pass(GL_ALWAYS, 0, none);
    offset_pass(GL_ALWAYS, -4, nearer);
    offset_pass(GL_ALWAYS, 4, farther);
    offset_pass(GL_LESS, -4, nearer_less);
    offset_pass(GL_LESS, 4, farther_less);
    /* 4 units of 0.5 to 2 steps of the buffer, in record units. */
    const double step = 4294967295.0 / (double)((1ull << bits) - 1);
    const double low = 4 * 0.5 * step, high = 4 * 2.0 * step;
    const double down = (double)none[OU_ZMIN] - (double)nearer[OU_ZMIN];
    const double up = (double)farther[OU_ZMIN] - (double)none[OU_ZMIN];
    const bool ok = none[OU_NOHC] == S * S && nearer[OU_ZMIN] == nearer[OU_ZMAX] &&
                    farther[OU_ZMIN] == farther[OU_ZMAX] && down >= low && down <= high && up >= low &&
                    up <= high && nearer_less[OU_NOHC] == S * S && nearer_less[OU_ZMIN] == nearer[OU_ZMIN] &&
                    farther_less[OU_NOHC] == 0 && farther_less[OU_PHC] == S * S;
    if (!ok)
        printf("%s: record z moved %.0f down and %.0f up, expected %.0f to %.0f; under LESS NOHC %u nearer "
               "(expected %d), %u farther (expected 0)\n",
               name, down, up, low, high, nearer_less[OU_NOHC], S * S, farther_less[OU_NOHC]);
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
    check_offset("offset-recorded-24-bit", 24);

    /* A framebuffer object with a 16-bit depth buffer. */
    struct ou_fbo_functions f = ou_fbo_functions();
    GLuint fbo, renderbuffers[2];
    f.GenFramebuffers(1, &fbo);
    f.GenRenderbuffers(2, renderbuffers);
    f.BindRenderbuffer(GL_RENDERBUFFER, renderbuffers[0]);
    f.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, S, S);
    f.BindRenderbuffer(GL_RENDERBUFFER, renderbuffers[1]);
    f.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, S, S);
    f.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    f.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers[0]);
    f.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers[1]);
    GLint depth_bits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    if (f.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE || depth_bits != 16) {
        printf("a framebuffer object with a DEPTH_COMPONENT16 buffer: status 0x%x, %d depth bits\n",
               f.CheckFramebufferStatus(GL_FRAMEBUFFER), depth_bits);
        subtest(false, "offset-recorded-16-bit");
        subtest(false, "not-quantized-16-bit");
        piglit_report_result(result);
    }
    check_offset("offset-recorded-16-bit", 16);

    {
        GLuint none[OU_BRIEF_SIZE], stored = 0;
        offset_pass(GL_ALWAYS, 0, none);   /* leaves the quad's depth in the buffer */
        glReadPixels(S / 2, S / 2, 1, 1, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, &stored);
        const double exact = (double)ou_depth(z_quad);
        const double recorded_error = fabs((double)none[OU_ZMIN] - exact);
        const double stored_error = fabs((double)stored - exact);
        /* float32 holds 0.3 to within 2^-25 of it: about 128 record units. */
        const bool ok = recorded_error <= 256 && stored_error > 4 * recorded_error && stored_error > 1024;
        if (!ok)
            printf("not-quantized-16-bit: the record is %.0f from z 0.3, the 16-bit buffer's value %.0f\n",
                   recorded_error, stored_error);
        subtest(ok && piglit_check_gl_error(GL_NO_ERROR), "not-quantized-16-bit");
    }
    piglit_report_result(result);
}
