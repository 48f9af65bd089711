/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: pass objects give the records RenderMode
 * gives, read later (spec MESAX_occlusion_unit_async, section 5.X.1 and
 * issues 2 to 6).
 *
 * The scene: depth cleared to 1, an occluder at z 0.25 over the left half
 * of a 64 x 64 window written into the depth buffer, then the pass draws a
 * quad over the whole window at z 0.5. Tiles: the left half (all hidden),
 * the right half (all visible) and a 16 x 16 square across the middle
 * (half visible). The reference is the same pass through RenderMode.
 *
 * Subtests:
 *   records-equal-render-mode        brief records of a pass object equal RenderMode's
 *   verbose-records-equal-render-mode   and so do verbose ones, lists included
 *   verbose-overflow-count           OCCLUSION_PASS_RESULT_MESAX returns RenderMode's
 *                                    overflow count
 *   end-writes-nothing               EndOcclusionPassMESAX leaves the buffers untouched,
 *                                    even once the pass is finished (glFinish)
 *   render-mode-is-render-after-end  RENDER_MODE and CURRENT_OCCLUSION_PASS_MESAX during
 *                                    and after the pass
 *   available-eventually             polling availability reaches TRUE
 *   no-wait-writes-when-available    RESULT_NO_WAIT writes the same records once available
 *   commands-after-end-not-counted   an occluder drawn after End over the visible half
 *                                    changes no record
 *   several-in-flight                four passes over different depth states, read in
 *                                    reverse order, each equal to its RenderMode reference
 *   buffers-taken-at-begin           buffers set after Begin do not receive the records
 *   begin-again-discards             a name begun twice holds the second pass
 *   query-buffer-records             with a buffer bound to QUERY_BUFFER, the records
 *                                    (and availability) go into it at the given offset
 *   deleted-in-flight-writes-nothing a pass deleted unread never writes its buffers
 *
 * The test ends with one pass in flight and one pass ended unread, which the
 * context's destruction must discard without writing or crashing.
 */
#include "ou_util.h"

#include <GL/glext.h>

enum { W = 64, H = 64, TILES = 3, LIST_WORDS = 8 + 2 * 64 };

static struct ou_async_functions a;
static const GLint tiles[4 * TILES] = {
    0, 0, 32, 64,    /* left: behind the occluder */
    32, 0, 32, 64,   /* right: visible */
    24, 24, 16, 16,  /* across the middle: half visible */
};

static void
set_buffers(GLuint (*records)[LIST_WORDS], GLsizei size)
{
    GLuint *buffers[TILES];
    GLsizei sizes[TILES];
    for (int i = 0; i < TILES; ++i) {
        ou_fill(records[i], LIST_WORDS);
        buffers[i] = records[i];
        sizes[i] = size;
    }
    OcclusionBuffersMESAX(TILES, sizes, buffers);
}

static void
depth_state(float occluder_right)
{
    glClear(GL_DEPTH_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ou_rect(0, 0, occluder_right, H, 0.25f);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

static void
draw_probe(void)
{
    ou_rect(0, 0, W, H, 0.5f);
}

/* The RenderMode reference of one pass over the current depth state. */
static GLint
reference(GLenum mode, GLsizei size, GLuint (*records)[LIST_WORDS])
{
    set_buffers(records, size);
    ScissorsMESAX(TILES, tiles);
    glRenderMode(mode);
    draw_probe();
    return glRenderMode(GL_RENDER);
}

static void
begin_probe(GLenum mode, GLuint pass, GLsizei size, GLuint (*records)[LIST_WORDS])
{
    set_buffers(records, size);
    ScissorsMESAX(TILES, tiles);
    a.BeginOcclusionPass(mode, pass);
    draw_probe();
    a.EndOcclusionPass();
}

static bool
same_records(const char *what, GLuint (*got)[LIST_WORDS], GLuint (*expected)[LIST_WORDS], int words)
{
    for (int i = 0; i < TILES; ++i) {
        /* Verbose lists are sets: compare them sorted. */
        if (words > OU_BRIEF_SIZE && got[i][OU_NOHC] <= (GLuint)(words - 8) / 2) {
            ou_sort_pairs(got[i] + 8, got[i][OU_NOHC]);
            ou_sort_pairs(expected[i] + 8, expected[i][OU_NOHC]);
        }
        for (int w = 0; w < words; ++w) {
            if (got[i][w] != expected[i][w]) {
                printf("%s: tile %d word %d is 0x%08x, RenderMode wrote 0x%08x\n", what, i, w, got[i][w],
                       expected[i][w]);
                return false;
            }
        }
    }
    return true;
}

static bool
untouched(const char *what, GLuint (*records)[LIST_WORDS])
{
    for (int i = 0; i < TILES; ++i)
        for (int w = 0; w < LIST_WORDS; ++w)
            if (records[i][w] != OU_SENTINEL) {
                printf("%s: tile %d word %d was written (0x%08x)\n", what, i, w, records[i][w]);
                return false;
            }
    return true;
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
    static GLuint ref[TILES][LIST_WORDS], got[TILES][LIST_WORDS], other[TILES][LIST_WORDS];
    GLuint pass[8];

    a = ou_init_async();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    a.GenOcclusionPasses(8, pass);

    /* Brief. */
    depth_state(32);
    reference(GL_BRIEF_OCCLUSION_MESAX, OU_BRIEF_SIZE, ref);
    begin_probe(GL_BRIEF_OCCLUSION_MESAX, pass[0], OU_BRIEF_SIZE, got);
    glFinish();
    subtest(untouched("end-writes-nothing", got) && piglit_check_gl_error(GL_NO_ERROR), "end-writes-nothing");
    GLint overflowed = -7;
    a.GetOcclusionPassiv(pass[0], GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    subtest(same_records("records-equal-render-mode", got, ref, OU_BRIEF_SIZE) && overflowed == 0 &&
                ref[1][OU_NOHC] == 32 * 64 && ref[0][OU_NOHC] == 0 && ref[2][OU_NOHC] == 8 * 16 &&
                piglit_check_gl_error(GL_NO_ERROR),
            "records-equal-render-mode");

    /* Verbose, room for 64 pairs: the left tile's list (empty) fits, the
     * right tile's 2048 pairs and the middle tile's 128 overflow, as in
     * RenderMode. */
    GLint ref_overflowed = reference(GL_VERBOSE_OCCLUSION_MESAX, LIST_WORDS, ref);
    begin_probe(GL_VERBOSE_OCCLUSION_MESAX, pass[1], LIST_WORDS, got);
    overflowed = -7;
    a.GetOcclusionPassiv(pass[1], GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    subtest(same_records("verbose-records-equal-render-mode", got, ref, LIST_WORDS) &&
                piglit_check_gl_error(GL_NO_ERROR),
            "verbose-records-equal-render-mode");
    if (overflowed != ref_overflowed || ref_overflowed != 2)
        printf("verbose-overflow-count: %d, RenderMode returned %d (2 expected)\n", overflowed, ref_overflowed);
    subtest(overflowed == ref_overflowed && ref_overflowed == 2, "verbose-overflow-count");

    /* Mode state during and after a pass. */
    {
        GLint mode_in = 0, current_in = 0, mode_after = 0, current_after = -1;
        set_buffers(got, OU_BRIEF_SIZE);
        ScissorsMESAX(TILES, tiles);
        a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass[2]);
        glGetIntegerv(GL_RENDER_MODE, &mode_in);
        glGetIntegerv(GL_CURRENT_OCCLUSION_PASS_MESAX, &current_in);
        draw_probe();
        a.EndOcclusionPass();
        glGetIntegerv(GL_RENDER_MODE, &mode_after);
        glGetIntegerv(GL_CURRENT_OCCLUSION_PASS_MESAX, &current_after);
        const bool ok = mode_in == GL_BRIEF_OCCLUSION_MESAX && current_in == (GLint)pass[2] &&
                        mode_after == GL_RENDER && current_after == 0;
        if (!ok)
            printf("render mode 0x%x then 0x%x, current pass %d then %d\n", mode_in, mode_after, current_in,
                   current_after);
        subtest(ok && piglit_check_gl_error(GL_NO_ERROR), "render-mode-is-render-after-end");

        /* The occluder drawn now covers the right half too: the pass, ended
         * before it, must not see it. */
        depth_state(64);
        subtest(ou_wait_available(&a, pass[2]), "available-eventually");
        overflowed = -7;
        a.GetOcclusionPassiv(pass[2], GL_OCCLUSION_PASS_RESULT_NO_WAIT_MESAX, &overflowed);
        {
            static GLuint ref2[TILES][LIST_WORDS];
            depth_state(32);
            reference(GL_BRIEF_OCCLUSION_MESAX, OU_BRIEF_SIZE, ref2);
            subtest(overflowed == 0 && same_records("no-wait-writes-when-available", got, ref2, OU_BRIEF_SIZE),
                    "no-wait-writes-when-available");
            subtest(got[1][OU_NOHC] == 32 * 64, "commands-after-end-not-counted");
        }
    }

    /* Several passes in flight over four depth states, read in reverse. */
    {
        static GLuint refs[4][TILES][LIST_WORDS], gots[4][TILES][LIST_WORDS];
        const float occluders[4] = {0, 16, 40, 64};
        for (int k = 0; k < 4; ++k) {
            depth_state(occluders[k]);
            reference(GL_BRIEF_OCCLUSION_MESAX, OU_BRIEF_SIZE, refs[k]);
            begin_probe(GL_BRIEF_OCCLUSION_MESAX, pass[3 + k], OU_BRIEF_SIZE, gots[k]);
        }
        bool ok = true;
        for (int k = 3; k >= 0; --k) {
            a.GetOcclusionPassiv(pass[3 + k], GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
            char what[64];
            snprintf(what, sizeof(what), "several-in-flight (pass %d)", k);
            ok = same_records(what, gots[k], refs[k], OU_BRIEF_SIZE) && ok;
        }
        subtest(ok && piglit_check_gl_error(GL_NO_ERROR), "several-in-flight");
    }

    /* Buffers are taken at Begin. */
    depth_state(32);
    reference(GL_BRIEF_OCCLUSION_MESAX, OU_BRIEF_SIZE, ref);
    begin_probe(GL_BRIEF_OCCLUSION_MESAX, pass[0], OU_BRIEF_SIZE, got);
    set_buffers(other, OU_BRIEF_SIZE);
    a.GetOcclusionPassiv(pass[0], GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    subtest(same_records("buffers-taken-at-begin", got, ref, OU_BRIEF_SIZE) &&
                untouched("buffers-taken-at-begin (buffers set after Begin)", other),
            "buffers-taken-at-begin");

    /* Begin again: the name holds the second pass. */
    depth_state(64);
    begin_probe(GL_BRIEF_OCCLUSION_MESAX, pass[1], OU_BRIEF_SIZE, other);
    depth_state(32);
    begin_probe(GL_BRIEF_OCCLUSION_MESAX, pass[1], OU_BRIEF_SIZE, got);
    a.GetOcclusionPassiv(pass[1], GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    subtest(same_records("begin-again-discards", got, ref, OU_BRIEF_SIZE) &&
                untouched("begin-again-discards (first pass's buffers)", other) && piglit_check_gl_error(GL_NO_ERROR),
            "begin-again-discards");

    /* Into a query buffer (ARB_query_buffer_object). */
    if (!piglit_is_extension_supported("GL_ARB_query_buffer_object")) {
        ou_subtest_dependency_missing("query-buffer-records", "GL_ARB_query_buffer_object");
    } else {
        PFNGLGENBUFFERSPROC GenBuffers = glGenBuffers;
        PFNGLBINDBUFFERPROC BindBuffer = glBindBuffer;
        PFNGLBUFFERDATAPROC BufferData = glBufferData;
        PFNGLGETBUFFERSUBDATAPROC GetBufferSubData =
            glGetBufferSubData;
        enum { OFFSET = 16, WORDS = 4 + TILES * OU_BRIEF_SIZE + 4 };
        GLuint buffer, init[WORDS], back[WORDS];
        for (int w = 0; w < WORDS; ++w)
            init[w] = OU_SENTINEL;
        GenBuffers(1, &buffer);
        BindBuffer(GL_QUERY_BUFFER, buffer);
        BufferData(GL_QUERY_BUFFER, sizeof(init), init, GL_DYNAMIC_COPY);
        begin_probe(GL_BRIEF_OCCLUSION_MESAX, pass[0], OU_BRIEF_SIZE, got);
        a.GetOcclusionPassiv(pass[0], GL_OCCLUSION_PASS_RESULT_MESAX, (GLint *)(intptr_t)OFFSET);
        a.GetOcclusionPassiv(pass[0], GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX, (GLint *)(intptr_t)0);
        bool ok = piglit_check_gl_error(GL_NO_ERROR);
        GetBufferSubData(GL_QUERY_BUFFER, 0, sizeof(back), back);
        BindBuffer(GL_QUERY_BUFFER, 0);
        ok = ok && untouched("query-buffer-records (client buffers)", got);
        if (back[0] != GL_TRUE || back[1] != OU_SENTINEL || back[3] != OU_SENTINEL) {
            printf("query-buffer-records: availability word %u, words 1..3 %x %x %x\n", back[0], back[1], back[2],
                   back[3]);
            ok = false;
        }
        for (int i = 0; i < TILES; ++i)
            for (int w = 0; w < OU_BRIEF_SIZE; ++w)
                if (back[4 + i * OU_BRIEF_SIZE + w] != ref[i][w]) {
                    printf("query-buffer-records: tile %d word %d is 0x%08x, expected 0x%08x\n", i, w,
                           back[4 + i * OU_BRIEF_SIZE + w], ref[i][w]);
                    ok = false;
                }
        if (back[WORDS - 1] != OU_SENTINEL) {
            printf("query-buffer-records: written past the records\n");
            ok = false;
        }
        subtest(ok, "query-buffer-records");
    }

    /* Deleted unread: never written. */
    begin_probe(GL_BRIEF_OCCLUSION_MESAX, pass[0], OU_BRIEF_SIZE, got);
    a.DeleteOcclusionPasses(1, &pass[0]);
    glFinish();
    subtest(untouched("deleted-in-flight-writes-nothing", got) && !a.IsOcclusionPass(pass[0]) &&
                piglit_check_gl_error(GL_NO_ERROR),
            "deleted-in-flight-writes-nothing");

    /* Left for the context's destruction: one pass ended unread, one in
     * progress. */
    begin_probe(GL_VERBOSE_OCCLUSION_MESAX, pass[1], LIST_WORDS, got);
    set_buffers(other, OU_BRIEF_SIZE);
    ScissorsMESAX(TILES, tiles);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass[2]);
    draw_probe();
    /* Submits the quad to the pass: Mesa 22.3.6 crashes in
     * OSMesaDestroyContext when immediate-mode vertices are still buffered,
     * in any render mode (a glBegin/glEnd quad and nothing else crashes it
     * too), which is not what this test is about. */
    glFlush();

    piglit_report_result(result);
}
