/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: the records of a pass written into a
 * query buffer (ARB_query_buffer_object; spec MESAX_occlusion_unit_async,
 * section 5.X.1 and issue 18). The region of the records is the sum of the
 * sizes the pass began with, whatever the mode and the counts; words of a
 * tile's region past its record keep their contents; an error writes
 * nothing; the storage flags of BufferStorage do not restrict the write.
 *
 * The pass: two tiles over a 32 x 32 window, depth test off, a 2 x 2
 * rectangle at (1, 1) in tile 0 (the left half) and nothing in tile 1 (the
 * right half). Buffers of 16 words each: a brief record occupies 8 of
 * them, a verbose one 8 + 2 * 4, all of them (tile 0), or 8 (tile 1).
 *
 * Subtests:
 *   region-must-fit-whole           a buffer of 24 words holds what a brief pass
 *                                   writes (words 0-7, 16-23) but not the region
 *                                   (32 words): INVALID_OPERATION, nothing written
 *   misaligned-offset-writes-nothing  offset 2: INVALID_VALUE, nothing written
 *   region-gaps-kept                at offset 16 bytes into 40 words: records at
 *                                   words 4 and 20, every other word unchanged
 *   verbose-equals-client-memory    a verbose pass read into the buffer and into
 *                                   client memory gives the same words
 *   storage-flags-do-not-restrict   a BufferStorage buffer of flags 0 receives
 *                                   the records
 *   availability-is-one-word        availability at the buffer's last word is
 *                                   written; one word further is INVALID_OPERATION
 */
#include "ou_util.h"

enum { S = 32, SIZE = 16, TILES = 2, BIG = 40 };

static struct ou_async_functions a;
static PFNGLGENBUFFERSPROC GenBuffers;
static PFNGLBINDBUFFERPROC BindBuffer;
static PFNGLBUFFERDATAPROC BufferData;
static PFNGLGETBUFFERSUBDATAPROC GetBufferSubData;
static GLuint client[TILES][SIZE];

static void
run_pass(GLuint pass, GLenum mode)
{
    static const GLint tiles[4 * TILES] = {0, 0, S / 2, S, S / 2, 0, S / 2, S};
    GLuint *buffers[TILES] = {client[0], client[1]};
    GLsizei sizes[TILES] = {SIZE, SIZE};
    for (int i = 0; i < TILES; ++i)
        ou_fill(client[i], SIZE);
    OcclusionBuffersMESAX(TILES, sizes, buffers);
    ScissorsMESAX(TILES, tiles);
    a.BeginOcclusionPass(mode, pass);
    ou_rect(1, 1, 3, 3, 0.5f);
    a.EndOcclusionPass();
    ScissorsMESAX(0, NULL);
}

/* A buffer bound to QUERY_BUFFER holding `words` sentinels. */
static GLuint
sentinel_buffer(int words)
{
    GLuint init[BIG], buffer;
    for (int w = 0; w < BIG; ++w)
        init[w] = OU_SENTINEL;
    GenBuffers(1, &buffer);
    BindBuffer(GL_QUERY_BUFFER, buffer);
    BufferData(GL_QUERY_BUFFER, 4 * words, init, GL_DYNAMIC_COPY);
    return buffer;
}

static bool
all_sentinels(const char *name, int words)
{
    GLuint back[BIG];
    GetBufferSubData(GL_QUERY_BUFFER, 0, 4 * words, back);
    for (int w = 0; w < words; ++w)
        if (back[w] != OU_SENTINEL) {
            printf("%s: word %d was written (0x%08x)\n", name, w, back[w]);
            return false;
        }
    return true;
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
    a = ou_init_async();
    if (!piglit_is_extension_supported("GL_ARB_query_buffer_object")) {
        static const char *names[] = {"region-must-fit-whole", "misaligned-offset-writes-nothing", "region-gaps-kept",
                                      "verbose-equals-client-memory", "storage-flags-do-not-restrict",
                                      "availability-is-one-word"};
        for (int i = 0; i < 6; ++i)
            ou_subtest_dependency_missing(names[i], "GL_ARB_query_buffer_object");
        piglit_report_result(result);
    }
    GenBuffers = glGenBuffers;
    BindBuffer = glBindBuffer;
    BufferData = glBufferData;
    GetBufferSubData = glGetBufferSubData;
    glDisable(GL_DEPTH_TEST);
    GLuint pass;
    a.GenOcclusionPasses(1, &pass);
    run_pass(pass, GL_BRIEF_OCCLUSION_MESAX);
    GLint overflowed = -1;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);   /* the reference, in client memory */
    GLuint brief[TILES][OU_BRIEF_SIZE];
    memcpy(brief[0], client[0], sizeof(brief[0]));
    memcpy(brief[1], client[1], sizeof(brief[1]));
    if (brief[0][OU_NOHC] != 4 || brief[1][OU_NOHC] != 0 || overflowed != 0) {
        printf("the reference records: NOHC %u and %u, expected 4 and 0\n", brief[0][OU_NOHC], brief[1][OU_NOHC]);
        piglit_report_result(PIGLIT_FAIL);
    }

    sentinel_buffer(24);
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, (GLint *)(intptr_t)0);
    subtest(piglit_check_gl_error(GL_INVALID_OPERATION) && all_sentinels("region-must-fit-whole", 24),
            "region-must-fit-whole");

    sentinel_buffer(BIG);
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, (GLint *)(intptr_t)2);
    subtest(piglit_check_gl_error(GL_INVALID_VALUE) && all_sentinels("misaligned-offset-writes-nothing", BIG),
            "misaligned-offset-writes-nothing");

    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, (GLint *)(intptr_t)16);
    bool ok = piglit_check_gl_error(GL_NO_ERROR);
    GLuint back[BIG];
    GetBufferSubData(GL_QUERY_BUFFER, 0, sizeof(back), back);
    for (int w = 0; w < BIG; ++w) {
        GLuint expected = OU_SENTINEL;
        if (w >= 4 && w < 4 + OU_BRIEF_SIZE)
            expected = brief[0][w - 4];
        else if (w >= 4 + SIZE && w < 4 + SIZE + OU_BRIEF_SIZE)
            expected = brief[1][w - 4 - SIZE];
        if (back[w] != expected) {
            printf("region-gaps-kept: word %d is 0x%08x, expected 0x%08x\n", w, back[w], expected);
            ok = false;
        }
    }
    subtest(ok, "region-gaps-kept");

    /* Verbose: the same pass read twice, into client memory and into the buffer. */
    run_pass(pass, GL_VERBOSE_OCCLUSION_MESAX);
    BindBuffer(GL_QUERY_BUFFER, 0);
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    ok = piglit_check_gl_error(GL_NO_ERROR) && overflowed == 0;
    sentinel_buffer(TILES * SIZE);
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, (GLint *)(intptr_t)0);
    ok = piglit_check_gl_error(GL_NO_ERROR) && ok;
    GetBufferSubData(GL_QUERY_BUFFER, 0, 4 * TILES * SIZE, back);
    for (int i = 0; i < TILES; ++i)
        for (int w = 0; w < SIZE; ++w)
            if (back[i * SIZE + w] != client[i][w]) {
                printf("verbose-equals-client-memory: tile %d word %d is 0x%08x in the buffer, 0x%08x in client "
                       "memory\n",
                       i, w, back[i * SIZE + w], client[i][w]);
                ok = false;
            }
    subtest(ok && client[0][OU_NOHC] == 4, "verbose-equals-client-memory");

    if (!piglit_is_extension_supported("GL_ARB_buffer_storage")) {
        ou_subtest_dependency_missing("storage-flags-do-not-restrict", "GL_ARB_buffer_storage");
    } else {
        PFNGLBUFFERSTORAGEPROC BufferStorage = glBufferStorage;
        GLuint buffer, init[TILES * SIZE];
        for (int w = 0; w < TILES * SIZE; ++w)
            init[w] = OU_SENTINEL;
        GenBuffers(1, &buffer);
        BindBuffer(GL_QUERY_BUFFER, buffer);
        BufferStorage(GL_QUERY_BUFFER, sizeof(init), init, 0);
        a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, (GLint *)(intptr_t)0);
        ok = piglit_check_gl_error(GL_NO_ERROR);
        GetBufferSubData(GL_QUERY_BUFFER, 0, sizeof(init), back);
        if (back[OU_NOHC] != 4 || back[SIZE + OU_PHC] != 0)
            printf("storage-flags-do-not-restrict: NOHC %u, tile 1 PHC %u\n", back[OU_NOHC], back[SIZE + OU_PHC]);
        subtest(ok && back[OU_NOHC] == 4 && back[SIZE + OU_PHC] == 0, "storage-flags-do-not-restrict");
    }

    sentinel_buffer(4);
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX, (GLint *)(intptr_t)12);
    ok = piglit_check_gl_error(GL_NO_ERROR);
    GetBufferSubData(GL_QUERY_BUFFER, 0, 16, back);
    ok = ok && back[0] == OU_SENTINEL && back[1] == OU_SENTINEL && back[2] == OU_SENTINEL && back[3] == GL_TRUE;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX, (GLint *)(intptr_t)16);
    ok = piglit_check_gl_error(GL_INVALID_OPERATION) && ok;
    subtest(ok, "availability-is-one-word");
    BindBuffer(GL_QUERY_BUFFER, 0);

    a.DeleteOcclusionPasses(1, &pass);
    piglit_report_result(result);
}
