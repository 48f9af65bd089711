/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: the framebuffer of an occlusion pass is fixed for
 * the pass against other contexts too (Dependencies on framebuffer objects
 * and Errors; issue 24). Context A draws into a 32 x 32 framebuffer object
 * (colour and depth renderbuffers, depth cleared to 1, test LESS: a quad at
 * depth 0.5 is visible). Context B shares A's objects and, during A's pass,
 * reallocates a renderbuffer attached to A's draw framebuffer
 * (RenderbufferStorage at 64 x 64), which B's RENDER mode allows and A
 * cannot refuse. Once A sees the new storage, A's drawing commands generate
 * INVALID_OPERATION and draw nothing, instead of testing fragments against
 * a depth buffer the pass did not begin with; the pass ends as ever and
 * counts what it drew before.
 *
 * Subtests:
 *   other-context-reallocates        B's RenderbufferStorage of A's depth buffer:
 *                                    no error in B, its width is 64
 *   draw-after-reallocation-invalid-operation  A (current again) draws the visible
 *                                    quad: INVALID_OPERATION
 *   rebind-then-draw-invalid-operation  A binds its draw framebuffer again (allowed)
 *                                    and draws: INVALID_OPERATION again
 *   pass-counts-before-reallocation  A's record: the quad drawn before B's call,
 *                                    NOHC 64, and RenderMode(RENDER) no error
 *   colour-reallocation-invalid-operation  the same with B reallocating the colour
 *                                    buffer (at 64 x 64)
 *   other-thread-reallocates         B, current in another thread while A stays
 *                                    current, reallocates the depth buffer again
 *                                    (32 x 32); after that thread has finished, A's
 *                                    DrawArrays generates INVALID_OPERATION, and
 *                                    so does its Begin once A has bound its draw
 *                                    framebuffer again; A's pass counts 0
 *   reallocation-inside-begin-end-error-at-end  B, in another thread, reallocates
 *                                    the depth buffer while A is between Begin and
 *                                    End of a quad: the primitive is either drawn
 *                                    (NOHC 64) or refused with INVALID_OPERATION
 *                                    reported right after End (NOHC 0), never by a
 *                                    later command (RenderMode: no error)
 *   draws-after-pass                 after the pass, on the reallocated buffers
 *                                    (status checked, depth cleared), a pass
 *                                    counts the quad: 64
 */
#include "ou_util.h"

#include "ou_two_contexts.h"

enum { S = 32 };

static struct ou_fbo_functions f;
static struct ou_two_contexts contexts;
static GLuint renderbuffers[2]; /* colour, depth */
static GLuint record[OU_BRIEF_SIZE];

static void
begin_pass(void)
{
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    const GLint tile[4] = {0, 0, S, S};
    ou_fill(record, OU_BRIEF_SIZE);
    ScissorsMESAX(1, tile);
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
}

/* B reallocates renderbuffer `index` of A's framebuffer (B is current). */
static GLenum
reallocate(int index, int size)
{
    static const GLenum formats[2] = {GL_RGBA8, GL_DEPTH_COMPONENT24};
    f.BindRenderbuffer(GL_RENDERBUFFER, renderbuffers[index]);
    f.RenderbufferStorage(GL_RENDERBUFFER, formats[index], size, size);
    return ou_first_error();
}

static GLint
renderbuffer_width(void)
{
    PFNGLGETRENDERBUFFERPARAMETERIVPROC GetRenderbufferParameteriv =
        glGetRenderbufferParameteriv;
    GLint width = -1;
    GetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_WIDTH, &width);
    return width;
}

static int
other_thread(void *arg)
{
    (void)arg;
    if (!ou_make_b_current(&contexts))
        return -1;
    const GLenum e = reallocate(1, S);
    glFinish();
    ou_release_current(&contexts);
    return (int)e;
}

/* The same, reallocating the depth buffer at twice the size. */
static int
other_thread_grows(void *arg)
{
    (void)arg;
    if (!ou_make_b_current(&contexts))
        return -1;
    const GLenum e = reallocate(1, 2 * S);
    glFinish();
    ou_release_current(&contexts);
    return (int)e;
}

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
    ou_init();
    f = ou_fbo_functions();
    contexts = ou_make_second_context(S);

    const GLuint fbo = ou_make_fbo(&f, S, S, 0, true, renderbuffers);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    ou_first_error();

    /* B reallocates A's depth buffer in the middle of A's pass. */
    begin_pass();
    ou_rect(4, 4, 12, 12, 0.5f);
    glFlush();
    ou_make_b_current(&contexts);
    const GLenum b_error = reallocate(1, 2 * S);
    const GLint b_width = renderbuffer_width();
    ou_make_a_current(&contexts);
    if (b_error != GL_NO_ERROR || b_width != 2 * S)
        printf("B's RenderbufferStorage: error 0x%x, width %d (expected none, %d)\n", b_error, b_width, 2 * S);
    subtest(b_error == GL_NO_ERROR && b_width == 2 * S, "other-context-reallocates");

    ou_rect(16, 16, 24, 24, 0.5f);
    GLenum e = ou_first_error();
    if (e != GL_INVALID_OPERATION)
        printf("A's quad after the reallocation: error 0x%x (expected INVALID_OPERATION)\n", e);
    subtest(e == GL_INVALID_OPERATION, "draw-after-reallocation-invalid-operation");

    f.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    const GLenum rebind = ou_first_error();
    ou_rect(16, 16, 24, 24, 0.5f);
    e = ou_first_error();
    if (rebind != GL_NO_ERROR || e != GL_INVALID_OPERATION)
        printf("rebinding: error 0x%x (expected none); a quad then: 0x%x (expected INVALID_OPERATION)\n", rebind, e);
    subtest(rebind == GL_NO_ERROR && e == GL_INVALID_OPERATION, "rebind-then-draw-invalid-operation");

    glRenderMode(GL_RENDER);
    e = ou_first_error();
    if (record[OU_NOHC] != 64 || e != GL_NO_ERROR)
        printf("A's pass: NOHC %u (expected 64, the quad before the reallocation), error 0x%x\n", record[OU_NOHC], e);
    subtest(record[OU_NOHC] == 64 && e == GL_NO_ERROR, "pass-counts-before-reallocation");

    /* The colour buffer: A's framebuffer is 64 x 64 in depth now, the
     * colour buffer still 32 x 32; B makes that 64 x 64 too. */
    glClear(GL_DEPTH_BUFFER_BIT);
    begin_pass();
    ou_rect(4, 4, 12, 12, 0.5f);
    ou_make_b_current(&contexts);
    const GLenum b_colour_error = reallocate(0, 2 * S);
    ou_make_a_current(&contexts);
    ou_rect(16, 16, 24, 24, 0.5f);
    e = ou_first_error();
    glRenderMode(GL_RENDER);
    if (b_colour_error != GL_NO_ERROR || e != GL_INVALID_OPERATION || record[OU_NOHC] != 64)
        printf("colour reallocation: B's error 0x%x, A's draw 0x%x (expected INVALID_OPERATION), NOHC %u (64)\n",
               b_colour_error, e, record[OU_NOHC]);
    subtest(b_colour_error == GL_NO_ERROR && e == GL_INVALID_OPERATION && record[OU_NOHC] == 64,
            "colour-reallocation-invalid-operation");

    /* B in a thread of its own, A current throughout. */
    glClear(GL_DEPTH_BUFFER_BIT);
    begin_pass();
    thrd_t thread;
    int thread_result = -1;
    const bool joined = thrd_create(&thread, other_thread, NULL) == thrd_success &&
                        thrd_join(thread, &thread_result) == thrd_success;
    static const GLfloat corners[4][3] = {{4, 4, 0.5f}, {12, 4, 0.5f}, {12, 12, 0.5f}, {4, 12, 0.5f}};
    glVertexPointer(3, GL_FLOAT, 0, corners);
    glEnableClientState(GL_VERTEX_ARRAY);
    glDrawArrays(GL_QUADS, 0, 4);
    glDisableClientState(GL_VERTEX_ARRAY);
    e = ou_first_error();
    f.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    ou_rect(4, 4, 12, 12, 0.5f);
    const GLenum begin_error = ou_first_error();
    glRenderMode(GL_RENDER);
    if (!joined || thread_result != GL_NO_ERROR || e != GL_INVALID_OPERATION || begin_error != GL_INVALID_OPERATION ||
        record[OU_NOHC] != 0)
        printf("other thread: joined %d, its error 0x%x; A's DrawArrays 0x%x and Begin after binding again 0x%x "
               "(expected INVALID_OPERATION), NOHC %u (0)\n",
               joined, thread_result, e, begin_error, record[OU_NOHC]);
    subtest(joined && thread_result == GL_NO_ERROR && e == GL_INVALID_OPERATION &&
                begin_error == GL_INVALID_OPERATION && record[OU_NOHC] == 0,
            "other-thread-reallocates");

    /* B reallocates while A is between Begin and End: the error, if the
     * quad is refused, is End's (spec section 5.X, Errors). */
    f.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glClear(GL_DEPTH_BUFFER_BIT);
    ou_first_error();
    begin_pass();
    glBegin(GL_QUADS);
    glVertex3f(4, 4, 0.5f);
    glVertex3f(12, 4, 0.5f);
    glVertex3f(12, 12, 0.5f);
    glVertex3f(4, 12, 0.5f);
    thread_result = -1;
    const bool joined_inside = thrd_create(&thread, other_thread_grows, NULL) == thrd_success &&
                               thrd_join(thread, &thread_result) == thrd_success;
    glEnd();
    const GLenum end_error = ou_first_error();
    glRenderMode(GL_RENDER);
    const GLenum later_error = ou_first_error();
    const bool drawn = end_error == GL_NO_ERROR && record[OU_NOHC] == 64;
    const bool refused_by_end = end_error == GL_INVALID_OPERATION && record[OU_NOHC] == 0;
    if (!joined_inside || thread_result != GL_NO_ERROR || !(drawn || refused_by_end) || later_error != GL_NO_ERROR)
        printf("reallocation inside Begin/End: joined %d, B's error 0x%x; error after End 0x%x, NOHC %u "
               "(expected none and 64, or INVALID_OPERATION and 0); error after RenderMode 0x%x (expected none)\n",
               joined_inside, thread_result, end_error, record[OU_NOHC], later_error);
    subtest(joined_inside && thread_result == GL_NO_ERROR && (drawn || refused_by_end) && later_error == GL_NO_ERROR,
            "reallocation-inside-begin-end-error-at-end");
    f.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);

    /* After the pass the framebuffer is A's to use again (its status
     * tested again after the other context's changes). */
    const GLenum status = f.CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
    glClear(GL_DEPTH_BUFFER_BIT);
    begin_pass();
    ou_rect(4, 4, 12, 12, 0.5f);
    glRenderMode(GL_RENDER);
    e = ou_first_error();
    if (status != GL_FRAMEBUFFER_COMPLETE || record[OU_NOHC] != 64 || e != GL_NO_ERROR)
        printf("a pass after the reallocations: status 0x%x, NOHC %u (expected 64), error 0x%x\n", status,
               record[OU_NOHC], e);
    subtest(status == GL_FRAMEBUFFER_COMPLETE && record[OU_NOHC] == 64 && e == GL_NO_ERROR, "draws-after-pass");
    piglit_report_result(result);
}
