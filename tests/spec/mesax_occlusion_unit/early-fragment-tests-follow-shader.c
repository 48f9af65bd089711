/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit with layout(early_fragment_tests): the stencil
 * and depth buffer tests and both counts precede the shader, so what
 * follows the shader changes neither count (spec section 4.1, issue 21):
 * a discard, the alpha test, and in a multisampled framebuffer the sample
 * mask output. This holds with no depth or stencil test enabled too.
 * (early-fragment-tests checks a discard with the depth test on.)
 * GL_SAMPLES_PASSED counts at the same place (OpenGL 4.6, section 14.9:
 * the early tests include the occlusion query's counting), so every
 * subtest also draws the rectangle in RENDER mode, depth writes off, inside
 * a GL_SAMPLES_PASSED query, which must count what it counts for the
 * rectangle without a shader (spec issue 21: the query and NOHC count at
 * the same place): 1024 in the single-sampled subtests, where that is
 * NOHC, and in the multisampled ones the reference query's count (samples,
 * where NOHC counts fragments).
 *
 * A 32 x 32 window (or a 4x framebuffer object of that size), depth
 * cleared to 1; the pass draws a window-sized rectangle at z 0.5.
 *
 * Subtests:
 *   discard-without-tests-removes-nothing   no depth or stencil test; the shader
 *                                           discards every other column:
 *                                           NOHC = PHC = 1024
 *   alpha-test-after-counts                 depth test LESS, the shader's alpha 0,
 *                                           the alpha test GREATER 0.5:
 *                                           NOHC = PHC = 1024
 *   multisample-discard-removes-nothing     4x, an occluder at z 0.25 over the
 *                                           left half, the discarding shader:
 *                                           PHC and NOHC are those of the rectangle
 *                                           without a shader
 *   multisample-sample-mask-output-after-counts  4x, the shader writes
 *                                           gl_SampleMask 0: the same
 * The multisample subtests skip where there is no 4x multisampling
 * (softpipe).
 */
#include "ou_util.h"

enum { S = 32 };

static PFNGLUSEPROGRAMPROC UseProgram;
static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;

/* GL_SAMPLES_PASSED of the rectangle drawn in RENDER mode, with depth
 * writes off so that the depth buffer stays as the pass saw it. */
static GLuint
samples_passed(void)
{
    GLuint query, samples = 0xdeadbeefu;
    GenQueries(1, &query);
    glDepthMask(GL_FALSE);
    BeginQuery(GL_SAMPLES_PASSED, query);
    ou_rect(0, 0, S, S, 0.5f);
    EndQuery(GL_SAMPLES_PASSED);
    glDepthMask(GL_TRUE);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    return samples;
}

static void
counts(GLuint *nohc, GLuint *phc)
{
    GLuint rec[1][OU_BRIEF_SIZE];
    GLuint *buffers[1] = {rec[0]};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    ou_fill(rec[0], OU_BRIEF_SIZE);
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    ou_rect(0, 0, S, S, 0.5f);
    glRenderMode(GL_RENDER);
    *nohc = rec[0][OU_NOHC];
    *phc = rec[0][OU_PHC];
}

static void
expect(const char *name, GLuint program, GLuint nohc, GLuint phc, GLuint samples_expected)
{
    GLuint got_nohc, got_phc;
    if (!program) {
        printf("%s: the shader did not build\n", name);
        subtest(false, name);
        return;
    }
    UseProgram(program);
    counts(&got_nohc, &got_phc);
    const GLuint samples = samples_passed();
    UseProgram(0);
    if (got_nohc != nohc || got_phc != phc)
        printf("%s: NOHC %u PHC %u, expected %u %u\n", name, got_nohc, got_phc, nohc, phc);
    if (samples != samples_expected)
        printf("%s: GL_SAMPLES_PASSED %u, expected %u\n", name, samples, samples_expected);
    subtest(got_nohc == nohc && got_phc == phc && samples == samples_expected && piglit_check_gl_error(GL_NO_ERROR),
            name);
}

static GLuint
early_program(const char *body)
{
    char source[512];
    snprintf(source, sizeof(source),
             "#version 150 compatibility\n"
             "#extension GL_ARB_shader_image_load_store : require\n"
             "#extension GL_ARB_sample_shading : enable\n"
             "layout(early_fragment_tests) in;\n"
             "void main() { %s }\n",
             body);
    return piglit_build_simple_program(NULL, source);
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
    UseProgram = glUseProgram;
    GenQueries = glGenQueries;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    GetQueryObjectuiv = glGetQueryObjectuiv;
    const GLuint discards =
        early_program("if (mod(floor(gl_FragCoord.x), 2.0) == 1.0) discard; gl_FragColor = vec4(1.0);");
    const GLuint transparent = early_program("gl_FragColor = vec4(1.0, 1.0, 1.0, 0.0);");

    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    expect("discard-without-tests-removes-nothing", discards, S * S, S * S, S * S);

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_ALPHA_TEST);
    glAlphaFunc(GL_GREATER, 0.5f);
    expect("alpha-test-after-counts", transparent, S * S, S * S, S * S);
    glDisable(GL_ALPHA_TEST);

    GLint max_samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    if (max_samples < 4) {
        printf("%s has no 4x multisampling (GL_MAX_SAMPLES %d)\n", (const char *)glGetString(GL_RENDERER), max_samples);
        piglit_report_subtest_result(PIGLIT_SKIP, "multisample-discard-removes-nothing");
        piglit_report_subtest_result(PIGLIT_SKIP, "multisample-sample-mask-output-after-counts");
        piglit_report_result(result);
    }
    const struct ou_fbo_functions f = ou_fbo_functions();
    GLuint rb[2];
    ou_make_fbo(&f, S, S, 4, true, rb);
    glEnable(GL_MULTISAMPLE);
    glClear(GL_DEPTH_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(0, 0, S / 2, S, 0.25f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    GLuint right, all;
    counts(&right, &all);
    const GLuint right_samples = samples_passed();
    printf("references without a shader: NOHC %u, PHC %u, GL_SAMPLES_PASSED %u\n", right, all, right_samples);
    expect("multisample-discard-removes-nothing", discards, right, all, right_samples);
    const GLuint masked = early_program("gl_SampleMask[0] = 0; gl_FragColor = vec4(1.0);");
    expect("multisample-sample-mask-output-after-counts", masked, right, all, right_samples);
    piglit_report_result(result);
}
