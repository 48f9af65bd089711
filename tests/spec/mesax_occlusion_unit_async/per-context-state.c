/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async's pass objects are per context, not shared
 * (spec section 5.X.1 and issue 14), and a pass begun by
 * BeginOcclusionPassMESAX is the state of its context alone. Context A is
 * the test's; context B shares A's objects (ou_two_contexts.h) and renders
 * into a buffer of the same size. Depth tests are off: every fragment
 * passes. The base extension's state: per-context-state.c.
 *
 * Subtests:
 *   pass-names-not-shared           a name generated in A is no pass object in B;
 *                                   B deleting it leaves A's object
 *   same-name-different-objects     B's own object of the same name is not A's:
 *                                   B's pass ended leaves A's object never begun
 *   async-pass-state-per-context    with a pass begun by BeginOcclusionPassMESAX in
 *                                   progress in A, B's RENDER_MODE is RENDER and
 *                                   B's rectangle is drawn
 *   async-pass-counts-own-context-only  that pass, ended in A, counts A's 8 x 8
 *                                   rectangle only: NOHC 64, PHC 64
 */
#include "ou_util.h"
#include "ou_two_contexts.h"

enum { S = 32 };

static struct ou_two_contexts c;

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = S;
    config.window_height = S;
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
    const struct ou_async_functions as = ou_init_async();
    c = ou_make_second_context(S);
    ou_make_b_current(&c);
    glViewport(0, 0, S, S);
    glMatrixMode(GL_PROJECTION);
    glOrtho(0, S, 0, S, 0, -1);
    glMatrixMode(GL_MODELVIEW);
    glDisable(GL_DEPTH_TEST);
    ou_make_a_current(&c);
    glDisable(GL_DEPTH_TEST);
    GLuint records[1][OU_BRIEF_SIZE];
    GLuint *buffers[1] = {records[0]};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};

    /* Pass objects. */
    GLuint name = 0;
    as.GenOcclusionPasses(1, &name);
    ou_make_b_current(&c);
    ScissorsMESAX(0, NULL);
    GLuint b_record[OU_BRIEF_SIZE];
    GLuint *b_buffers[1] = {b_record};
    OcclusionBuffersMESAX(1, sizes, b_buffers);
    const bool unknown_in_b = !as.IsOcclusionPass(name);
    as.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, name);
    const bool begin_fails_in_b = piglit_check_gl_error(GL_INVALID_OPERATION);
    as.DeleteOcclusionPasses(1, &name);
    const bool delete_ignored_in_b = piglit_check_gl_error(GL_NO_ERROR);
    ou_make_a_current(&c);
    const bool still_in_a = as.IsOcclusionPass(name);
    if (!unknown_in_b || !begin_fails_in_b || !delete_ignored_in_b || !still_in_a)
        printf("pass %u: unknown in B %d, Begin fails in B %d, Delete ignored in B %d, still in A %d\n", name,
               unknown_in_b, begin_fails_in_b, delete_ignored_in_b, still_in_a);
    subtest(unknown_in_b && begin_fails_in_b && delete_ignored_in_b && still_in_a, "pass-names-not-shared");

    /* B makes objects of its own until one has A's name, begins and ends a
     * pass on it; A's object of that name was never begun. */
    ou_make_b_current(&c);
    GLuint b_names[64];
    as.GenOcclusionPasses(64, b_names);
    int same = -1;
    for (int i = 0; i < 64; ++i)
        if (b_names[i] == name)
            same = i;
    bool b_pass = false;
    if (same >= 0) {
        as.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, name);
        ou_rect(0, 0, 4, 4, 0.5f);
        as.EndOcclusionPass();
        GLint overflowed = -1;
        as.GetOcclusionPassiv(name, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
        b_pass = piglit_check_gl_error(GL_NO_ERROR) && overflowed == 0 && b_record[OU_NOHC] == 16;
    }
    ou_make_a_current(&c);
    GLint available = 7;
    as.GetOcclusionPassiv(name, GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX, &available);
    const bool a_never_begun = piglit_check_gl_error(GL_INVALID_OPERATION) && available == 7;
    if (same < 0 || !b_pass || !a_never_begun)
        printf("B's object %u: %s, its pass %s; A's object %s\n", name, same >= 0 ? "made" : "not among 64 names",
               b_pass ? "read" : "not read", a_never_begun ? "never begun" : "has a pass");
    subtest(same >= 0 && b_pass && a_never_begun, "same-name-different-objects");

    /* A pass of A begun by BeginOcclusionPassMESAX, with B drawing in the
     * middle of it. */
    GLuint a_pass;
    as.GenOcclusionPasses(1, &a_pass);
    ScissorsMESAX(0, NULL);
    OcclusionBuffersMESAX(1, sizes, buffers);
    ou_fill(records[0], OU_BRIEF_SIZE);
    as.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, a_pass);
    ou_rect(0, 0, 8, 8, 0.5f);

    ou_make_b_current(&c);
    const GLint b_mode_async = ou_get_integer(GL_RENDER_MODE);
    static const unsigned char red[4] = {255, 0, 0, 255};
    glClear(GL_COLOR_BUFFER_BIT);
    glColor4ub(255, 0, 0, 255);
    ou_rect(0, 0, S, S, 0.5f);
    const bool b_drew_red = ou_probe_rect_rgba_ub(0, 0, S, S, red, 0);
    if (b_mode_async != GL_RENDER)
        printf("B's RENDER_MODE is 0x%x during A's BeginOcclusionPassMESAX pass\n", b_mode_async);
    subtest(b_mode_async == GL_RENDER && b_drew_red && piglit_check_gl_error(GL_NO_ERROR),
            "async-pass-state-per-context");
    glFinish();

    ou_make_a_current(&c);
    as.EndOcclusionPass();
    GLint a_overflowed = -1;
    as.GetOcclusionPassiv(a_pass, GL_OCCLUSION_PASS_RESULT_MESAX, &a_overflowed);
    if (records[0][OU_NOHC] != 64 || records[0][OU_PHC] != 64)
        printf("A's pass: NOHC %u PHC %u, expected 64 and 64\n", records[0][OU_NOHC], records[0][OU_PHC]);
    subtest(records[0][OU_NOHC] == 64 && records[0][OU_PHC] == 64 && a_overflowed == 0 &&
                piglit_check_gl_error(GL_NO_ERROR),
            "async-pass-counts-own-context-only");

    ou_destroy_second_context(&c);
    piglit_report_result(result);
}
