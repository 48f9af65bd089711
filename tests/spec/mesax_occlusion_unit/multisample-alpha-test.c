/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: in a multisampled framebuffer too, the alpha
 * test follows PHC (spec issue 1 and section 4.1): a fragment that fails it
 * counts in PHC and not in NOHC, as in a single-sampled one.
 *
 * A 4x framebuffer object of 32 x 32, no depth test; the pass draws a
 * window-sized rectangle whose shader gives alpha 0 left of x = 16 and 1
 * right of it, with the alpha test GREATER 0.5. The rectangle is two
 * triangles with fragments of their own along the diagonal (issue 6), so
 * the references are the unit's counts with the alpha test off: PHC of the
 * whole rectangle (all), and PHC with the scissor test cut to the right
 * half (right).
 *
 * Subtests:
 *   single-sampled-agrees   in the single-sampled window first: NOHC 512,
 *                           PHC 1024
 *   alpha-test-after-phc    in the 4x framebuffer: NOHC right, PHC all
 *
 * softpipe has no multisampling (GL_MAX_SAMPLES below 4): there the test
 * skips, as multisample-fragments does.
 */
#include "ou_util.h"

enum { S = 32 };

static void
counts(GLuint *nohc, GLuint *phc)
{
    GLuint record[OU_BRIEF_SIZE];
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    ou_fill(record, OU_BRIEF_SIZE);
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    ou_rect(0, 0, S, S, 0.5f);
    glRenderMode(GL_RENDER);
    *nohc = record[OU_NOHC];
    *phc = record[OU_PHC];
}

static void
expect(const char *name, GLuint nohc, GLuint phc)
{
    GLuint got_nohc, got_phc;
    glEnable(GL_ALPHA_TEST);
    glAlphaFunc(GL_GREATER, 0.5f);
    counts(&got_nohc, &got_phc);
    glDisable(GL_ALPHA_TEST);
    if (got_nohc != nohc || got_phc != phc)
        printf("%s: NOHC %u PHC %u, expected %u %u\n", name, got_nohc, got_phc, nohc, phc);
    subtest(got_nohc == nohc && got_phc == phc && piglit_check_gl_error(GL_NO_ERROR), name);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 20;
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
    GLint max_samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    if (max_samples < 4) {
        printf("%s has no 4x multisampling (GL_MAX_SAMPLES %d)\n", (const char *)glGetString(GL_RENDERER), max_samples);
        piglit_report_result(PIGLIT_SKIP);
    }
    PFNGLUSEPROGRAMPROC UseProgram = glUseProgram;
    const GLuint program = piglit_build_simple_program(NULL,
        "#version 110\n"
        "void main() { gl_FragColor = vec4(1.0, 1.0, 1.0, gl_FragCoord.x < 16.0 ? 0.0 : 1.0); }\n");
    if (!program) {
        printf("the shader did not build\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    glDisable(GL_DEPTH_TEST);
    UseProgram(program);

    expect("single-sampled-agrees", S * S / 2, S * S);

    const struct ou_fbo_functions f = ou_fbo_functions();
    GLuint rb[2];
    ou_make_fbo(&f, S, S, 4, true, rb);
    glEnable(GL_MULTISAMPLE);
    GLuint all, right, ignored;
    counts(&ignored, &all);
    glEnable(GL_SCISSOR_TEST);
    glScissor(S / 2, 0, S / 2, S);
    counts(&ignored, &right);
    glDisable(GL_SCISSOR_TEST);
    printf("references: PHC %u, right of x = 16 %u\n", all, right);
    expect("alpha-test-after-phc", right, all);
    UseProgram(0);
    piglit_report_result(result);
}
