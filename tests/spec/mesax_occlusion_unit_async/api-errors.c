/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: every error of the spec's Errors section,
 * each with the state read back afterwards to see that the failing command
 * changed nothing (spec MESAX_occlusion_unit_async, Errors).
 *
 * Subtests are named for the command and the error.
 */
#include "ou_util.h"

#include <GL/glext.h>
#include <math.h>

static struct ou_async_functions a;
static GLuint record[2][OU_BRIEF_SIZE];

static void
one_buffer(void)
{
    GLuint *buffers[1] = {record[0]};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    OcclusionBuffersMESAX(1, sizes, buffers);
    ScissorsMESAX(0, NULL);
}

static GLint
get_int(GLenum pname)
{
    GLint v = -12345;
    glGetIntegerv(pname, &v);
    return v;
}

/* True when the render mode and current pass are as given. */
static bool
mode_is(GLenum mode, GLuint current)
{
    const GLint m = get_int(GL_RENDER_MODE), c = get_int(GL_CURRENT_OCCLUSION_PASS_MESAX);
    if (m != (GLint)mode || c != (GLint)current) {
        printf("render mode 0x%x (expected 0x%x), current pass %d (expected %u)\n", m, mode, c, current);
        return false;
    }
    return true;
}

static void
expect(bool ok, GLenum error, const char *name)
{
    const bool e = piglit_check_gl_error(error);
    subtest(ok && e && piglit_check_gl_error(GL_NO_ERROR), name);
}

/* An ended pass over one default tile. */
static void
ended_pass(GLuint pass)
{
    one_buffer();
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    ou_rect(0, 0, 8, 8, 0.5f);
    a.EndOcclusionPass();
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = 32;
    config.window_height = 32;
    config.window_visual = PIGLIT_GL_VISUAL_RGBA | PIGLIT_GL_VISUAL_DEPTH | PIGLIT_GL_VISUAL_STENCIL;
    config.khr_no_error_support = PIGLIT_HAS_ERRORS;

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
    GLuint p[4];
    GLint params;

    a = ou_init_async();
    expect(mode_is(GL_RENDER, 0), GL_NO_ERROR, "initial-state");

    /* Gen and Delete. */
    p[0] = 777;
    a.GenOcclusionPasses(-1, p);
    expect(p[0] == 777, GL_INVALID_VALUE, "gen-negative-count-invalid-value");
    a.GenOcclusionPasses(4, p);
    expect(p[0] && p[1] && p[2] && p[3] && a.IsOcclusionPass(p[0]) && a.IsOcclusionPass(p[3]) &&
               !a.IsOcclusionPass(0),
           GL_NO_ERROR, "gen-creates-objects");
    a.DeleteOcclusionPasses(-1, p);
    expect(a.IsOcclusionPass(p[0]), GL_INVALID_VALUE, "delete-negative-count-invalid-value");

    /* Begin. */
    one_buffer();
    a.BeginOcclusionPass(GL_SELECT, p[0]);
    expect(mode_is(GL_RENDER, 0), GL_INVALID_ENUM, "begin-bad-mode-invalid-enum");
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, 0);
    expect(mode_is(GL_RENDER, 0), GL_INVALID_OPERATION, "begin-name-zero-invalid-operation");
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, p[3] + 1000);
    expect(mode_is(GL_RENDER, 0), GL_INVALID_OPERATION, "begin-unknown-name-invalid-operation");
    {
        GLuint select[16];
        glSelectBuffer(16, select);
        glRenderMode(GL_SELECT);
        a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, p[0]);
        const bool ok = mode_is(GL_SELECT, 0);
        glRenderMode(GL_RENDER);
        expect(ok, GL_INVALID_OPERATION, "begin-in-select-invalid-operation");
    }
    {
        const GLint two[8] = {0, 0, 8, 8, 8, 8, 8, 8};
        ScissorsMESAX(2, two);   /* two tiles, one buffer */
        a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, p[0]);
        const bool ok = mode_is(GL_RENDER, 0);
        ScissorsMESAX(0, NULL);
        expect(ok, GL_INVALID_OPERATION, "begin-too-few-buffers-invalid-operation");
    }
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, p[0]);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, p[1]);
    expect(mode_is(GL_BRIEF_OCCLUSION_MESAX, p[0]), GL_INVALID_OPERATION, "begin-during-pass-invalid-operation");
    ou_rect(0, 0, 8, 8, 0.5f);   /* p[0]'s pass: 64 fragments */

    /* RenderMode, Get and Delete during a pass. */
    params = 55;
    GLint r = glRenderMode(GL_RENDER);
    expect(r == 0 && mode_is(GL_BRIEF_OCCLUSION_MESAX, p[0]), GL_INVALID_OPERATION,
           "render-mode-during-pass-invalid-operation");
    a.GetOcclusionPassiv(p[0], GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX, &params);
    expect(params == 55, GL_INVALID_OPERATION, "get-pass-in-progress-invalid-operation");
    {
        GLuint both[2] = {p[1], p[0]};
        a.DeleteOcclusionPasses(2, both);
        expect(a.IsOcclusionPass(p[0]) && a.IsOcclusionPass(p[1]), GL_INVALID_OPERATION,
               "delete-pass-in-progress-invalid-operation-deletes-none");
    }
    a.EndOcclusionPass();
    expect(mode_is(GL_RENDER, 0), GL_NO_ERROR, "end-pass");

    /* End without a pass, and after RenderMode's own pass. */
    a.EndOcclusionPass();
    expect(mode_is(GL_RENDER, 0), GL_INVALID_OPERATION, "end-without-pass-invalid-operation");
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    a.EndOcclusionPass();
    {
        const bool ok = mode_is(GL_BRIEF_OCCLUSION_MESAX, 0);
        glRenderMode(GL_RENDER);
        expect(ok, GL_INVALID_OPERATION, "end-render-mode-pass-invalid-operation");
    }

    /* Get. */
    params = 55;
    a.GetOcclusionPassiv(p[0], GL_QUERY_RESULT, &params);
    expect(params == 55, GL_INVALID_ENUM, "get-bad-pname-invalid-enum");
    a.GetOcclusionPassiv(p[2], GL_OCCLUSION_PASS_RESULT_MESAX, &params);
    expect(params == 55, GL_INVALID_OPERATION, "get-never-begun-invalid-operation");
    a.GetOcclusionPassiv(p[3] + 1000, GL_OCCLUSION_PASS_RESULT_MESAX, &params);
    expect(params == 55, GL_INVALID_OPERATION, "get-unknown-name-invalid-operation");
    a.GetOcclusionPassiv(p[0], GL_OCCLUSION_PASS_RESULT_MESAX, &params);
    expect(params == 0 && record[0][OU_NOHC] == 64, GL_NO_ERROR, "get-result");

    /* Between Begin and End. */
    glBegin(GL_POINTS);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, p[1]);
    glEnd();
    expect(mode_is(GL_RENDER, 0), GL_INVALID_OPERATION, "begin-inside-begin-end-invalid-operation");

    /* Conditional rendering on a tile. */
    ended_pass(p[1]);
    a.BeginConditionalRenderOcclusionTile(p[1], 0, 0, 0.0f, GL_QUERY_BY_REGION_WAIT);
    expect(true, GL_INVALID_ENUM, "conditional-bad-mode-invalid-enum");
    a.BeginConditionalRenderOcclusionTile(p[1], 1, 0, 0.0f, GL_QUERY_WAIT);
    expect(true, GL_INVALID_VALUE, "conditional-tile-out-of-range-invalid-value");
    a.BeginConditionalRenderOcclusionTile(p[1], 0, 0, -0.5f, GL_QUERY_WAIT);
    expect(true, GL_INVALID_VALUE, "conditional-negative-ratio-invalid-value");
    a.BeginConditionalRenderOcclusionTile(p[1], 0, 0, NAN, GL_QUERY_WAIT);
    expect(true, GL_INVALID_VALUE, "conditional-nan-ratio-invalid-value");
    a.BeginConditionalRenderOcclusionTile(p[1], 0, 0, INFINITY, GL_QUERY_WAIT);
    expect(true, GL_INVALID_VALUE, "conditional-infinite-ratio-invalid-value");
    a.BeginConditionalRenderOcclusionTile(p[2], 0, 0, 0.0f, GL_QUERY_WAIT);
    expect(true, GL_INVALID_OPERATION, "conditional-never-begun-invalid-operation");
    a.EndConditionalRenderOcclusionTile();
    expect(true, GL_INVALID_OPERATION, "conditional-end-without-begin-invalid-operation");

    /* The calls above must not have begun anything: a clear under no
     * condition still clears. */
    glClearColor(0, 1, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    {
        const unsigned char green[4] = {0, 255, 0, 255};
        expect(ou_probe_rect_rgba_ub(0, 0, 32, 32, green, 0), GL_NO_ERROR,
               "failed-conditional-begins-leave-rendering-unconditional");
    }

    a.BeginConditionalRenderOcclusionTile(p[1], 0, 0, 0.0f, GL_QUERY_WAIT);
    expect(true, GL_NO_ERROR, "conditional-begin");
    a.BeginConditionalRenderOcclusionTile(p[1], 0, 0, 0.0f, GL_QUERY_WAIT);
    expect(true, GL_INVALID_OPERATION, "conditional-twice-invalid-operation");
    a.DeleteOcclusionPasses(1, &p[1]);
    expect(a.IsOcclusionPass(p[1]), GL_INVALID_OPERATION, "delete-conditional-pass-invalid-operation");
    one_buffer();
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, p[1]);
    expect(mode_is(GL_RENDER, 0), GL_INVALID_OPERATION, "begin-conditional-pass-invalid-operation");
    if (piglit_is_extension_supported("GL_NV_conditional_render")) {
        PFNGLBEGINCONDITIONALRENDERNVPROC BeginConditionalRenderNV =
            glBeginConditionalRenderNV;
        PFNGLGENQUERIESPROC GenQueries = glGenQueries;
        PFNGLBEGINQUERYPROC BeginQuery = glBeginQuery;
        PFNGLENDQUERYPROC EndQuery = glEndQuery;
        GLuint q;   /* a query NV_conditional_render would take */
        GenQueries(1, &q);
        BeginQuery(GL_SAMPLES_PASSED, q);
        EndQuery(GL_SAMPLES_PASSED);
        BeginConditionalRenderNV(q, GL_QUERY_WAIT_NV);
        expect(true, GL_INVALID_OPERATION, "nv-conditional-during-tile-conditional-invalid-operation");
    } else {
        ou_subtest_unsupported("nv-conditional-during-tile-conditional-invalid-operation", "GL_NV_conditional_render");
    }
    a.EndConditionalRenderOcclusionTile();
    expect(true, GL_NO_ERROR, "conditional-end");

    /* Query buffer offsets. */
    if (!piglit_is_extension_supported("GL_ARB_query_buffer_object")) {
        ou_subtest_dependency_missing("query-buffer-offset-errors", "GL_ARB_query_buffer_object");
    } else {
        PFNGLGENBUFFERSPROC GenBuffers = glGenBuffers;
        PFNGLBINDBUFFERPROC BindBuffer = glBindBuffer;
        PFNGLBUFFERDATAPROC BufferData = glBufferData;
        GLuint buffer;
        GenBuffers(1, &buffer);
        BindBuffer(GL_QUERY_BUFFER, buffer);
        BufferData(GL_QUERY_BUFFER, 4 * OU_BRIEF_SIZE, NULL, GL_DYNAMIC_COPY);
        bool ok = true;
        a.GetOcclusionPassiv(p[0], GL_OCCLUSION_PASS_RESULT_MESAX, (GLint *)(intptr_t)-4);
        ok = piglit_check_gl_error(GL_INVALID_VALUE) && ok;
        a.GetOcclusionPassiv(p[0], GL_OCCLUSION_PASS_RESULT_MESAX, (GLint *)(intptr_t)2);
        ok = piglit_check_gl_error(GL_INVALID_VALUE) && ok;
        a.GetOcclusionPassiv(p[0], GL_OCCLUSION_PASS_RESULT_MESAX, (GLint *)(intptr_t)4);
        ok = piglit_check_gl_error(GL_INVALID_OPERATION) && ok;   /* 8 words from word 1: one past */
        a.GetOcclusionPassiv(p[0], GL_OCCLUSION_PASS_RESULT_MESAX, (GLint *)(intptr_t)0);
        ok = piglit_check_gl_error(GL_NO_ERROR) && ok;
        BindBuffer(GL_QUERY_BUFFER, 0);
        subtest(ok, "query-buffer-offset-errors");
    }

    /* Deleting and Is. */
    a.DeleteOcclusionPasses(4, p);
    expect(!a.IsOcclusionPass(p[0]) && !a.IsOcclusionPass(p[3]), GL_NO_ERROR, "delete-then-is-false");
    {
        GLuint zero_and_unused[2] = {0, p[3] + 1000};
        a.DeleteOcclusionPasses(2, zero_and_unused);
        expect(true, GL_NO_ERROR, "delete-unused-names-ignored");
    }

    piglit_report_result(result);
}
