/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit and the other per-fragment operations (spec
 * issues 1, 7 and 10): PHC counts fragments entering the per-fragment tests
 * (after scissor and discard), NOHC those passing alpha, stencil and depth
 * tests; an occlusion pass writes no depth, so its own primitives never
 * occlude each other; an active SAMPLES_PASSED query counts NOHC and an
 * ANY_SAMPLES_PASSED query whether it is non-zero; a draw that conditional
 * rendering discards adds nothing to the tiles, one it lets through counts;
 * nor does a draw with RASTERIZER_DISCARD enabled.
 * Object: a 20 x 10 rectangle at z = 0.5, left half behind an occluder at
 * z = 0.25 where noted. Counts exact.
 */
#include "ou_util.h"

#define W 64
#define H 64

static GLuint rec[1][OU_BRIEF_SIZE];

static void
expect(const char *name, GLuint nohc, GLuint phc)
{
    bool ok = rec[0][OU_NOHC] == nohc && rec[0][OU_PHC] == phc && piglit_check_gl_error(GL_NO_ERROR);
    if (!ok)
        printf("%s: NOHC %u PHC %u, expected %u %u\n", name, rec[0][OU_NOHC], rec[0][OU_PHC], nohc, phc);
    piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "%s", name);
    if (!ok)
        result = PIGLIT_FAIL;
}

static void draw_target(void) { ou_rect(10, 20, 30, 30, 0.5f); }
static void draw_target_twice(void) { ou_rect(10, 20, 30, 30, 0.5f); ou_rect(10, 20, 30, 30, 0.6f); }

static void
scene_with_occluder(void)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearDepth(1.0);
    glClearStencil(0);
    glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    ou_rect(10, 20, 20, 30, 0.25f);
}

static void draw_occluded_half(void) { ou_rect(10, 20, 20, 30, 0.5f); }

/* An ANY_SAMPLES_PASSED query around a pass's draw: FALSE for the hidden
 * half of the object, TRUE for the object. */
static void
test_any_samples_passed(void)
{
    if (!piglit_is_extension_supported("GL_ARB_occlusion_query2")) {
        ou_subtest_unsupported("any-samples-passed-query-in-pass", "GL_ARB_occlusion_query2");
        return;
    }
    PFNGLGENQUERIESPROC GenQueries = glGenQueries;
    PFNGLBEGINQUERYPROC BeginQuery = glBeginQuery;
    PFNGLENDQUERYPROC EndQuery = glEndQuery;
    PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv =
        glGetQueryObjectuiv;
    GLuint query[2], any[2] = {7, 7};
    void (*draws[2])(void) = {draw_occluded_half, draw_target};
    GLuint nohc[2];
    GenQueries(2, query);
    scene_with_occluder();
    for (int i = 0; i < 2; ++i) {
        BeginQuery(GL_ANY_SAMPLES_PASSED, query[i]);
        ou_brief_pass(0, NULL, rec, draws[i]);
        EndQuery(GL_ANY_SAMPLES_PASSED);
        GetQueryObjectuiv(query[i], GL_QUERY_RESULT, &any[i]);
        nohc[i] = rec[0][OU_NOHC];
    }
    const bool ok = piglit_check_gl_error(GL_NO_ERROR) && any[0] == GL_FALSE && nohc[0] == 0 &&
                    any[1] == GL_TRUE && nohc[1] == 100;
    if (!ok)
        printf("ANY_SAMPLES_PASSED %u and %u, NOHC %u and %u; expected FALSE, TRUE, 0, 100\n", any[0], any[1],
               nohc[0], nohc[1]);
    subtest(ok, "any-samples-passed-query-in-pass");
}

/* Conditional rendering on a SAMPLES_PASSED query taken in GL_RENDER: the
 * hidden half's query (0) discards the pass's draw, the object's lets it
 * through. */
static void
test_conditional_render(void)
{
    PFNGLBEGINCONDITIONALRENDERPROC BeginConditionalRender =
        glBeginConditionalRender;
    PFNGLENDCONDITIONALRENDERPROC EndConditionalRender =
        glEndConditionalRender;
    if (!piglit_is_extension_supported("GL_NV_conditional_render")) {
        ou_subtest_unsupported("conditional-render-discarded-draw-not-counted", "GL_NV_conditional_render");
        ou_subtest_unsupported("conditional-render-passed-draw-counted", "GL_NV_conditional_render");
        return;
    }
    PFNGLGENQUERIESPROC GenQueries = glGenQueries;
    PFNGLBEGINQUERYPROC BeginQuery = glBeginQuery;
    PFNGLENDQUERYPROC EndQuery = glEndQuery;
    GLuint query[2];
    GenQueries(2, query);
    scene_with_occluder();
    glDepthMask(GL_FALSE);   /* the queried draws leave the depth buffer as it is */
    BeginQuery(GL_SAMPLES_PASSED, query[0]);
    draw_occluded_half();
    EndQuery(GL_SAMPLES_PASSED);
    BeginQuery(GL_SAMPLES_PASSED, query[1]);
    draw_target();
    EndQuery(GL_SAMPLES_PASSED);
    glDepthMask(GL_TRUE);

    for (int i = 0; i < 2; ++i) {
        GLuint record[OU_BRIEF_SIZE];
        GLuint *buffers[1] = {record};
        const GLsizei size = OU_BRIEF_SIZE;
        ou_fill(record, OU_BRIEF_SIZE);
        OcclusionBuffersMESAX(1, &size, buffers);
        glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
        BeginConditionalRender(query[i], GL_QUERY_WAIT);
        draw_target();
        EndConditionalRender();
        glRenderMode(GL_RENDER);
        const GLuint nohc = i == 0 ? 0 : 100, phc = i == 0 ? 0 : 200;
        const bool ok = piglit_check_gl_error(GL_NO_ERROR) && record[OU_NOHC] == nohc && record[OU_PHC] == phc;
        if (!ok)
            printf("conditional draw %d: NOHC %u PHC %u, expected %u %u\n", i, record[OU_NOHC], record[OU_PHC], nohc,
                   phc);
        subtest(ok, i == 0 ? "conditional-render-discarded-draw-not-counted" : "conditional-render-passed-draw-counted");
    }
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 20;
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

    scene_with_occluder();
    ou_brief_pass(0, NULL, rec, draw_target);
    expect("depth-less", 100, 200);

    scene_with_occluder();
    glDepthFunc(GL_GREATER);   /* passes only where the occluder is: stored 0.25 < 0.5 */
    ou_brief_pass(0, NULL, rec, draw_target);
    expect("depth-greater", 100, 200);
    glDepthFunc(GL_LESS);

    scene_with_occluder();
    glDepthMask(GL_FALSE);
    ou_brief_pass(0, NULL, rec, draw_target);
    expect("depth-mask-off", 100, 200);
    glDepthMask(GL_TRUE);

    /* The pass writes no depth: the second, farther copy is not occluded by the first. */
    scene_with_occluder();
    ou_brief_pass(0, NULL, rec, draw_target_twice);
    expect("pass-does-not-occlude-itself", 200, 400);

    /* Stencil: only the right 5 columns have stencil 1; PHC counts before the test. */
    scene_with_occluder();
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glDisable(GL_DEPTH_TEST);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(25, 0, W, H, 0.0f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glEnable(GL_DEPTH_TEST);
    glStencilFunc(GL_EQUAL, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    ou_brief_pass(0, NULL, rec, draw_target);
    glDisable(GL_STENCIL_TEST);
    expect("stencil-equal", 50, 200);

    /* Alpha test: a failing alpha removes fragments from NOHC, not from PHC. */
    scene_with_occluder();
    glEnable(GL_ALPHA_TEST);
    glAlphaFunc(GL_GREATER, 0.5f);
    glColor4f(1, 1, 1, 0.25f);
    ou_brief_pass(0, NULL, rec, draw_target);
    expect("alpha-test-fails", 0, 200);
    glColor4f(1, 1, 1, 0.75f);
    ou_brief_pass(0, NULL, rec, draw_target);
    expect("alpha-test-passes", 100, 200);
    glDisable(GL_ALPHA_TEST);
    glColor4f(1, 1, 1, 1);

    /* Scissor test with an explicit tile: the scissor test comes first. */
    scene_with_occluder();
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 25, H);
    const GLint whole[4] = {0, 0, W, H};
    ou_brief_pass(1, whole, rec, draw_target);
    glDisable(GL_SCISSOR_TEST);
    expect("scissor-test-before-tile", 50, 150);

    /* Discard in a fragment shader removes fragments from PHC too: the
     * shader discards the columns x < 20, the left half of the object.
     * GLSL 1.10 is part of every context these tests run in, so a shader
     * that does not build fails the subtest. */
    GLuint program = piglit_build_simple_program(NULL,
        "#version 110\n"
        "void main() { if (gl_FragCoord.x < 20.0) discard; gl_FragColor = vec4(1.0); }\n");
    PFNGLUSEPROGRAMPROC UseProgram = glUseProgram;
    if (program && UseProgram) {
        glDisable(GL_DEPTH_TEST);
        UseProgram(program);
        ou_brief_pass(0, NULL, rec, draw_target);
        UseProgram(0);
        expect("shader-discard", 100, 100);
    } else {
        printf("shader-discard: the GLSL 1.10 shader did not build\n");
        piglit_report_subtest_result(PIGLIT_FAIL, "shader-discard");
        result = PIGLIT_FAIL;
    }

    /* An active SAMPLES_PASSED query counts what NOHC counts. */
    PFNGLGENQUERIESPROC GenQueries = glGenQueries;
    PFNGLBEGINQUERYPROC BeginQuery = glBeginQuery;
    PFNGLENDQUERYPROC EndQuery = glEndQuery;
    PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv =
        glGetQueryObjectuiv;
    GLuint query, samples = 0;
    scene_with_occluder();
    GenQueries(1, &query);
    BeginQuery(GL_SAMPLES_PASSED, query);
    ou_brief_pass(0, NULL, rec, draw_target);
    EndQuery(GL_SAMPLES_PASSED);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    bool ok = samples == rec[0][OU_NOHC] && samples == 100;
    if (!ok)
        printf("SAMPLES_PASSED %u, NOHC %u\n", samples, rec[0][OU_NOHC]);
    piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "samples-passed-query-equals-nohc");
    if (!ok)
        result = PIGLIT_FAIL;

    test_any_samples_passed();
    test_conditional_render();

    /* RASTERIZER_DISCARD: no fragments, nothing counted. */
    scene_with_occluder();
    glEnable(GL_RASTERIZER_DISCARD);
    ou_brief_pass(0, NULL, rec, draw_target);
    glDisable(GL_RASTERIZER_DISCARD);
    expect("rasterizer-discard-counts-nothing", 0, 0);

    piglit_report_result(result);
}
