/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: the multisample fragment operations come before
 * PHC (spec section 4.1, issue 20). Sample coverage, SAMPLE_MASK,
 * alpha-to-coverage and the shader's sample mask output decide which
 * samples of a fragment are covered before the unit counts it: a fragment
 * left with none counts nowhere, one left with any counts once. Sample
 * shading still counts fragments, not invocations. (The alpha test, which
 * follows PHC, is not exercised here: in a 4x framebuffer llvmpipe still
 * counts PHC after it, against issue 1.) A shader whose outputs feed
 * these operations must run in a pass (section 3.11), so the
 * alpha-to-coverage and sample-mask-output subtests also fail if the pass
 * skipped shading.
 *
 * A 4x framebuffer object of 32 x 32, depth cleared to 1 and an occluder
 * at z 0.25 over the left half; the pass draws a window-sized rectangle at
 * z 0.5. The rectangle is two triangles, and where their shared diagonal
 * crosses a pixel each has a fragment of its own (issue 6), so the
 * references are the unit's own counts with every multisample operation
 * off: PHC of the whole rectangle (all), NOHC (the fragments right of the
 * occluder, right). multisample-fragments checks those against rendering.
 *
 * Subtests:
 *   sample-coverage-zero-counts-nothing     SampleCoverage(0, FALSE): 0/0
 *   sample-coverage-one-counts-all          SampleCoverage(1, FALSE): as the references
 *   sample-mask-zero-counts-nothing         SampleMaski(0, 0): 0/0
 *   sample-mask-one-sample-counts-fragments SampleMaski(0, 0xf): as the references
 *   alpha-to-coverage-before-phc            alpha 0 left of x = 16, 1 right: PHC and
 *                                           NOHC are right's
 *   sample-mask-output-before-phc           gl_SampleMask 0 left of x = 16: the same
 *   sample-shading-counts-fragments         MinSampleShading(1): PHC all, NOHC right
 *
 * and, with the depth test off, one tile, (8, 8) to (24, 24), and a
 * triangle over the whole window (clipped into several, whose shared
 * edges' pixels have a fragment of each: issue 6), a pass whose shader
 * clears the coverage left of x = 16 must count exactly what a shader that
 * discards those fragments counts, a shader the GL must run, and less than
 * one that keeps them all:
 *   sample-mask-output-counts               gl_SampleMask: the discarding
 *                                           shader's record, box included
 *   alpha-to-coverage-output-counts         alpha-to-coverage: the same
 *
 * softpipe has no multisampling (GL_MAX_SAMPLES below 4): there the test
 * skips, as multisample-fragments does.
 */
#include "ou_util.h"

enum { S = 32 };

static PFNGLUSEPROGRAMPROC UseProgram;
static PFNGLSAMPLECOVERAGEPROC SampleCoverage;
static PFNGLSAMPLEMASKIPROC SampleMaski;
static PFNGLMINSAMPLESHADINGPROC MinSampleShading;

/* The pass's counts of the rectangle at z 0.5. */
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
    counts(&got_nohc, &got_phc);
    const bool ok = got_nohc == nohc && got_phc == phc;
    if (!ok)
        printf("%s: NOHC %u PHC %u, expected %u %u\n", name, got_nohc, got_phc, nohc, phc);
    subtest(ok && piglit_check_gl_error(GL_NO_ERROR), name);
}

static void
triangle_over_window(void)
{
    glBegin(GL_TRIANGLES);
    glVertex3f(-100, -100, 0.5f);
    glVertex3f(300, -100, 0.5f);
    glVertex3f(-100, 300, 0.5f);
    glEnd();
}

/* The record of a pass over the triangle in tile (8, 8, 16, 16) with the
 * shader `source`; false when it does not build. */
static bool
triangle_pass(const char *source, bool alpha_to_coverage, GLuint record[OU_BRIEF_SIZE])
{
    static const GLint tile[4] = {8, 8, 16, 16};
    const GLuint p = piglit_build_simple_program(NULL, source);
    if (!p)
        return false;
    GLuint records[1][OU_BRIEF_SIZE];
    UseProgram(p);
    if (alpha_to_coverage)
        glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    ou_brief_pass(1, tile, records, triangle_over_window);
    glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    UseProgram(0);
    memcpy(record, records[0], sizeof(records[0]));
    return true;
}

static GLuint discarding[OU_BRIEF_SIZE], keeping[OU_BRIEF_SIZE];

static void
counts_as_discarding(const char *name, const char *source, bool alpha_to_coverage)
{
    GLuint record[OU_BRIEF_SIZE];
    if (!triangle_pass(source, alpha_to_coverage, record)) {
        printf("%s: the shader did not build\n", name);
        subtest(false, name);
        return;
    }
    const bool ok = ou_check_record(name, record, discarding, 0) && record[OU_PHC] < keeping[OU_PHC];
    if (!ok)
        printf("%s: PHC %u; the discarding shader's %u, the keeping shader's %u\n", name, record[OU_PHC],
               discarding[OU_PHC], keeping[OU_PHC]);
    subtest(ok && piglit_check_gl_error(GL_NO_ERROR), name);
}

static GLuint
program(const char *name, const char *source)
{
    const GLuint p = piglit_build_simple_program(NULL, source);
    if (!p) {
        printf("%s: the shader did not build\n", name);
        subtest(false, name);
    }
    return p;
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
    UseProgram = glUseProgram;
    SampleCoverage = glSampleCoverage;
    SampleMaski = glSampleMaski;
    MinSampleShading = glMinSampleShading;
    if (!UseProgram || !SampleCoverage || !SampleMaski || !MinSampleShading) {
        printf("glUseProgram, glSampleCoverage, glSampleMaski or glMinSampleShading is missing\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    const struct ou_fbo_functions f = ou_fbo_functions();
    GLuint rb[2];
    ou_make_fbo(&f, S, S, 4, true, rb);
    glEnable(GL_MULTISAMPLE);

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(0, 0, S / 2, S, 0.25f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

    GLuint right, all;
    counts(&right, &all);
    printf("references: PHC %u (the rectangle's fragments), NOHC %u (those right of the occluder)\n", all, right);
    if (all < S * S || right < S * S / 2 || right >= all) {
        printf("the references are not those of a %d x %d rectangle half behind an occluder\n", S, S);
        piglit_report_result(PIGLIT_FAIL);
    }

    glEnable(GL_SAMPLE_COVERAGE);
    SampleCoverage(0.0f, GL_FALSE);
    expect("sample-coverage-zero-counts-nothing", 0, 0);
    SampleCoverage(1.0f, GL_FALSE);
    expect("sample-coverage-one-counts-all", right, all);
    glDisable(GL_SAMPLE_COVERAGE);

    glEnable(GL_SAMPLE_MASK);
    SampleMaski(0, 0);
    expect("sample-mask-zero-counts-nothing", 0, 0);
    SampleMaski(0, 0xf);
    expect("sample-mask-one-sample-counts-fragments", right, all);
    glDisable(GL_SAMPLE_MASK);

    /* The fragments right of x = 16 with no occluder, cut by the scissor
     * test, which precedes the unit: NOHC = PHC = right_alone. */
    glClear(GL_DEPTH_BUFFER_BIT);
    GLuint right_alone, ignored;
    glEnable(GL_SCISSOR_TEST);
    glScissor(S / 2, 0, S / 2, S);
    counts(&right_alone, &ignored);
    glDisable(GL_SCISSOR_TEST);

    /* Fragments left of x = 16 get alpha 0, those right of it alpha 1:
     * alpha-to-coverage leaves the left ones no sample, the right ones all. */
    const char *alpha_source = "#version 110\n"
                               "void main() { gl_FragColor = vec4(1.0, 1.0, 1.0, gl_FragCoord.x < 16.0 ? 0.0 : 1.0); }\n";
    GLuint p = program("alpha-to-coverage-before-phc", alpha_source);
    if (p) {
        UseProgram(p);
        glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
        expect("alpha-to-coverage-before-phc", right_alone, right_alone);
        glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
        UseProgram(0);
    }

    const char *mask_source = "#version 130\n"
                              "#extension GL_ARB_sample_shading : require\n"
                              "void main() { gl_SampleMask[0] = gl_FragCoord.x < 16.0 ? 0 : -1;"
                              " gl_FragColor = vec4(1.0); }\n";
    p = program("sample-mask-output-before-phc", mask_source);
    if (p) {
        UseProgram(p);
        expect("sample-mask-output-before-phc", right_alone, right_alone);
        UseProgram(0);
    }

    /* The occluder again, for sample shading. */
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(0, 0, S / 2, S, 0.25f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

    const char *shaded_source = "#version 130\n"
                                "#extension GL_ARB_sample_shading : require\n"
                                "void main() { gl_FragColor = vec4(float(gl_SampleID) / 4.0); }\n";
    p = program("sample-shading-counts-fragments", shaded_source);
    if (p) {
        UseProgram(p);
        glEnable(GL_SAMPLE_SHADING);
        MinSampleShading(1.0f);
        expect("sample-shading-counts-fragments", right, all);
        glDisable(GL_SAMPLE_SHADING);
        UseProgram(0);
    }

    /* Shaders whose outputs clear coverage count as one that discards. */
    glDisable(GL_DEPTH_TEST);
    if (!triangle_pass("#version 150 compatibility\n"
                       "out vec4 colour;\n"
                       "void main() {\n"
                       "  if (gl_FragCoord.x < 16.0) discard;\n"
                       "  colour = vec4(1.0);\n"
                       "}\n",
                       false, discarding) ||
        !triangle_pass("#version 150 compatibility\n"
                       "out vec4 colour;\n"
                       "void main() { colour = vec4(1.0); }\n",
                       false, keeping)) {
        printf("the reference shaders did not build\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    if (discarding[OU_XMIN] != 16 || discarding[OU_NOHC] == 0 || discarding[OU_PHC] >= keeping[OU_PHC]) {
        printf("the discarding shader counts %u (x from %u), the keeping one %u\n", discarding[OU_PHC],
               discarding[OU_XMIN], keeping[OU_PHC]);
        piglit_report_result(PIGLIT_FAIL);
    }
    counts_as_discarding("sample-mask-output-counts",
                         "#version 150 compatibility\n"
                         "#extension GL_ARB_sample_shading : require\n"
                         "out vec4 colour;\n"
                         "void main() {\n"
                         "  gl_SampleMask[0] = gl_FragCoord.x < 16.0 ? 0 : -1;\n"
                         "  colour = vec4(1.0);\n"
                         "}\n",
                         false);
    counts_as_discarding("alpha-to-coverage-output-counts",
                         "#version 150 compatibility\n"
                         "out vec4 colour;\n"
                         "void main() {\n"
                         "  colour = vec4(1.0, 1.0, 1.0, gl_FragCoord.x < 16.0 ? 0.0 : 1.0);\n"
                         "}\n",
                         true);
    piglit_report_result(result);
}
