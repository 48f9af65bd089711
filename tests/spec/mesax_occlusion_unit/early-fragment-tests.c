/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit with layout(early_fragment_tests): the tests come
 * before the shader, as in RENDER mode, so a discard in the shader removes
 * nothing from PHC and NOHC, and an occlusion query active during a pass
 * counts what it counts in RENDER mode (section "Dependencies on
 * ARB_shader_image_load_store ..."). The shader discards every other
 * column of a 64 x 64 quad.
 *
 * Subtests:
 *   early-tests-counts-ignore-discard     NOHC = PHC = 4096
 *   samples-passed-in-pass-equals-render  GL_SAMPLES_PASSED during a brief
 *                                         pass equals GL_RENDER's
 *   samples-passed-counts-before-discard  ... and is 4096: with early tests the
 *                                         occlusion query counts at the tests,
 *                                         before the shader (OpenGL 4.2 and
 *                                         later, section "Early Fragment Tests"),
 *                                         so it equals NOHC
 *   late-tests-counts-see-discard         without the layout: NOHC 2048
 */
#include "ou_util.h"

#define S 64

static PFNGLUSEPROGRAMPROC UseProgram;
static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;

static GLuint
samples_passed(GLenum mode, GLuint *record)
{
    GLuint query, samples = 0;
    GenQueries(1, &query);
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {8};
    if (mode != GL_RENDER) {
        OcclusionBuffersMESAX(1, sizes, buffers);
        glRenderMode(mode);
    }
    BeginQuery(GL_SAMPLES_PASSED, query);
    ou_rect(0, 0, S, S, 0.5f);
    EndQuery(GL_SAMPLES_PASSED);
    if (mode != GL_RENDER)
        glRenderMode(GL_RENDER);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    return samples;
}

static GLuint
build(bool early)
{
    char source[512];
    snprintf(source, sizeof(source),
             "#version 150 compatibility\n"
             "#extension GL_ARB_shader_image_load_store : require\n"
             "%s"
             "out vec4 colour;\n"
             "void main() {\n"
             "  if (mod(floor(gl_FragCoord.x), 2.0) == 1.0) discard;\n"
             "  colour = vec4(1.0);\n"
             "}\n",
             early ? "layout(early_fragment_tests) in;\n" : "");
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
    const GLuint early = build(true), late = build(false);
    if (!early || !late) {
        printf("a shader with layout(early_fragment_tests) or ARB_shader_image_load_store did not build\n");
        subtest(false, "early-tests-counts-ignore-discard");
        piglit_report_result(result);
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glDepthMask(GL_FALSE);   /* every draw meets the cleared depth */

    GLuint record[8];
    UseProgram(early);
    const GLuint render = samples_passed(GL_RENDER, record);
    const GLuint in_pass = samples_passed(GL_BRIEF_OCCLUSION_MESAX, record);
    const bool counts = record[OU_NOHC] == S * S && record[OU_PHC] == S * S;
    if (!counts)
        printf("early tests: NOHC %u PHC %u, expected %d\n", record[OU_NOHC], record[OU_PHC], S * S);
    subtest(counts, "early-tests-counts-ignore-discard");
    if (render != in_pass)
        printf("SAMPLES_PASSED: %u in GL_RENDER, %u during a pass\n", render, in_pass);
    subtest(render == in_pass, "samples-passed-in-pass-equals-render");
    if (render != S * S || in_pass != record[OU_NOHC])
        printf("SAMPLES_PASSED %u in GL_RENDER and %u in the pass, NOHC %u; expected %d\n", render, in_pass,
               record[OU_NOHC], S * S);
    subtest(render == S * S && in_pass == record[OU_NOHC], "samples-passed-counts-before-discard");

    UseProgram(late);
    samples_passed(GL_BRIEF_OCCLUSION_MESAX, record);
    if (record[OU_NOHC] != S * S / 2)
        printf("late tests: NOHC %u, expected %d\n", record[OU_NOHC], S * S / 2);
    subtest(record[OU_NOHC] == S * S / 2, "late-tests-counts-see-discard");
    UseProgram(0);
    piglit_report_result(result);
}
