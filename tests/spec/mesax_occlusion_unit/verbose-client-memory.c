/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: when client memory holds the records (section
 * 5.X). The GL writes buffers[i] only when RenderMode leaves the occlusion
 * mode, and then only the words of the record (8 header words, the pairs
 * and, on overflow, the terminator); until then the application may read
 * and write the buffers, and what it wrote past the record survives.
 *
 * Subtests:
 *   nothing-written-during-pass
 *       a verbose pass draws 200 fragments into a tile with room for 300
 *       pairs; before RenderMode(GL_RENDER) every word of the buffer still
 *       holds the sentinel.
 *   application-writes-during-pass-survive-past-record
 *       the application writes a word past where the record will end
 *       during the pass; after the pass it is unchanged.
 *   overflow-keeps-words-past-terminator
 *       a list that overflows a 110-word buffer ends with the terminator
 *       at word 108; word 109, which the application wrote during the
 *       pass, keeps its value (nothing stale is restored over it).
 *
 * Huge declarations (2^31 - 1 words a tile) are verbose-memory-bounded's,
 * and OUT_OF_MEMORY's records out-of-memory-fault-injection's.
 */
#include "ou_util.h"

#define W 32
#define H 32

static GLuint buffer[8 + 2 * 300];

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
    ou_init();
    glDisable(GL_DEPTH_TEST);

    /* 20 x 10 = 200 fragments in one tile over the window. */
    GLuint *buffers[1] = {buffer};
    GLsizei sizes[1] = {8 + 2 * 300};
    ou_fill(buffer, sizes[0]);
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    ou_rect(2, 3, 22, 13, 0.5f);
    glFinish();
    bool untouched = true;
    for (int i = 0; i < sizes[0]; ++i)
        untouched = untouched && buffer[i] == OU_SENTINEL;
    const GLuint past = 8 + 2 * 250;   /* past the record of 200 pairs */
    buffer[past] = 0x12345678u;
    glRenderMode(GL_RENDER);
    if (!untouched)
        printf("the GL wrote into the buffer during the pass\n");
    subtest(untouched, "nothing-written-during-pass");
    subtest(buffer[OU_NOHC] == 200 && buffer[past] == 0x12345678u &&
                buffer[8 + 2 * 200] == OU_SENTINEL,
            "application-writes-during-pass-survive-past-record");

    /* A buffer of 8 + 102 words: 50 pairs, the terminator at word 108
     * (8 + 2 * floor((110 - 9) / 2)), and word 109 the application's. */
    static GLuint small[8 + 102];
    sizes[0] = 8 + 102;
    buffers[0] = small;
    ou_fill(small, sizes[0]);
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    ou_rect(2, 3, 22, 13, 0.5f);
    glFinish();
    small[sizes[0] - 1] = 0xabcdef01u;
    const GLint overflowed = glRenderMode(GL_RENDER);
    const GLuint terminator_at = 8 + 2 * ((sizes[0] - 9) / 2);
    const bool ok = overflowed == 1 && small[terminator_at] == 0xffffffffu &&
                    small[sizes[0] - 1] == 0xabcdef01u;
    if (!ok)
        printf("overflow: returned %d, word %u = 0x%08x, last word 0x%08x\n", overflowed, terminator_at,
               small[terminator_at], small[sizes[0] - 1]);
    subtest(ok, "overflow-keeps-words-past-terminator");

    piglit_report_result(result);
}
