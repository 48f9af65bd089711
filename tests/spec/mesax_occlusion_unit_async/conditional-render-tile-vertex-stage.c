/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: a draw that conditional rendering on a
 * tile discards has no effect at all (spec MESAX_occlusion_unit_async,
 * section 5.X.2): its primitives are not counted by PRIMITIVES_GENERATED,
 * its vertices not by VERTEX_SHADER_INVOCATIONS_ARB
 * (ARB_pipeline_statistics_query), even when the condition is begun while
 * its pass is still rasterizing (a pass of many quads, not read), which is
 * when llvmpipe with rasterizer threads may leave the decision to its
 * rasterizer.
 *
 * The pass: depth cleared to 1, an occluder at z 0.25 over the left half
 * of a 256 x 256 window, the pass's quads at z 0.5; tile 0 is the left
 * half (NOHC 0), tile 1 the window (NOHC 32768).
 *
 * The same quad drawn without a condition gives the counts a drawn quad
 * has (softpipe counts PRIMITIVES_GENERATED only into transform feedback,
 * so 0 there; both drivers count the vertex shader's invocations); at least
 * one must be non-zero, or the test could not see the discarded draw's.
 *
 * Subtests (each with the pass anew, the queries around the condition's
 * Begin, a quad of 4 vertices drawn with DrawArrays(TRIANGLE_FAN), and the
 * condition's End):
 *   discarded-draw-generates-no-primitives   tile 0: PRIMITIVES_GENERATED 0
 *   discarded-draw-invokes-no-vertex-shader  tile 0: VERTEX_SHADER_INVOCATIONS 0
 *   drawn-draw-counts-as-unconditional       tile 1: the counts of the quad
 *                                            drawn without a condition
 */
#include "ou_util.h"

enum { W = 256, H = 256, PASS_QUADS = 64 };

#ifndef GL_VERTEX_SHADER_INVOCATIONS_ARB
#define GL_VERTEX_SHADER_INVOCATIONS_ARB 0x82F0
#endif

static struct ou_async_functions a;
static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;
static bool have_statistics;

static void
run_pass(GLuint pass)
{
    static GLuint records[2][OU_BRIEF_SIZE];
    static const GLint tiles[8] = {0, 0, W / 2, H, 0, 0, W, H};
    GLuint *buffers[2] = {records[0], records[1]};
    GLsizei sizes[2] = {OU_BRIEF_SIZE, OU_BRIEF_SIZE};

    glEnable(GL_DEPTH_TEST);
    glClear(GL_DEPTH_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(0, 0, W / 2, H, 0.25f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    OcclusionBuffersMESAX(2, sizes, buffers);
    ScissorsMESAX(2, tiles);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    for (int i = 0; i < PASS_QUADS; ++i)
        ou_rect(0, 0, W, H, 0.5f);
    a.EndOcclusionPass();
    ScissorsMESAX(0, NULL);
    glDisable(GL_DEPTH_TEST);
}

/* The pass anew, then a quad under the condition on `tile` (none when
 * `conditional` is false), counted by a PRIMITIVES_GENERATED query and,
 * where there is one, a vertex shader invocations query. */
static void
counted_quad(GLuint pass, bool conditional, GLuint tile, GLuint *primitives, GLuint *invocations)
{
    static const GLfloat quad[8] = {0, 0, W, 0, W, H, 0, H};
    GLuint query[2];

    run_pass(pass);
    GenQueries(2, query);
    BeginQuery(GL_PRIMITIVES_GENERATED, query[0]);
    if (have_statistics)
        BeginQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB, query[1]);
    if (conditional)
        a.BeginConditionalRenderOcclusionTile(pass, tile, 0, 0.0f, GL_QUERY_WAIT);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(2, GL_FLOAT, 0, quad);
    glDrawArrays(GL_TRIANGLE_FAN, 0, 4);
    glDisableClientState(GL_VERTEX_ARRAY);
    if (conditional)
        a.EndConditionalRenderOcclusionTile();
    EndQuery(GL_PRIMITIVES_GENERATED);
    if (have_statistics)
        EndQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB);
    *primitives = *invocations = 0xdeadbeefu;
    GetQueryObjectuiv(query[0], GL_QUERY_RESULT, primitives);
    if (have_statistics)
        GetQueryObjectuiv(query[1], GL_QUERY_RESULT, invocations);
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
    GLuint pass, primitives, invocations, drawn_primitives, drawn_invocations;

    a = ou_init_async();
    GenQueries = glGenQueries;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    GetQueryObjectuiv = glGetQueryObjectuiv;
    if (!GenQueries || !BeginQuery || !EndQuery || !GetQueryObjectuiv) {
        ou_subtest_unsupported("discarded-draw-generates-no-primitives", "OpenGL 1.5 queries");
        piglit_report_result(result);
    }
    have_statistics = piglit_is_extension_supported("GL_ARB_pipeline_statistics_query");
    a.GenOcclusionPasses(1, &pass);

    counted_quad(pass, false, 0, &drawn_primitives, &drawn_invocations);
    if (drawn_primitives == 0 && (!have_statistics || drawn_invocations == 0)) {
        printf("the quad drawn without a condition counts no primitive and no invocation\n");
        piglit_report_result(PIGLIT_FAIL);
    }

    counted_quad(pass, true, 0, &primitives, &invocations);
    if (primitives != 0)
        printf("PRIMITIVES_GENERATED of the discarded draw is %u, expected 0\n", primitives);
    subtest(primitives == 0 && piglit_check_gl_error(GL_NO_ERROR), "discarded-draw-generates-no-primitives");
    if (have_statistics) {
        if (invocations != 0)
            printf("VERTEX_SHADER_INVOCATIONS of the discarded draw is %u, expected 0\n", invocations);
        subtest(invocations == 0, "discarded-draw-invokes-no-vertex-shader");
    } else {
        ou_subtest_dependency_missing("discarded-draw-invokes-no-vertex-shader", "GL_ARB_pipeline_statistics_query");
    }

    counted_quad(pass, true, 1, &primitives, &invocations);
    {
        const bool ok = primitives == drawn_primitives && (!have_statistics || invocations == drawn_invocations);
        if (!ok)
            printf("the quad drawn under a passing condition: PRIMITIVES_GENERATED %u, VERTEX_SHADER_INVOCATIONS %u; "
                   "without a condition %u and %u\n",
                   primitives, invocations, drawn_primitives, drawn_invocations);
        subtest(ok && piglit_check_gl_error(GL_NO_ERROR), "drawn-draw-counts-as-unconditional");
    }

    piglit_report_result(result);
}
