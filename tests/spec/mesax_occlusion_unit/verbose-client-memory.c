/*
 * GL_MESAX_occlusion_unit: when client memory holds the records (section
 * 5.X). The GL writes buffers[i] only when RenderMode leaves the occlusion
 * mode, and then only the words of the record (8 header words, the pairs
 * and, on overflow, the terminator); until then the application may read
 * and write the buffers, and what it wrote past the record survives.
 * If the GL cannot allocate what a verbose pass needs, it generates
 * OUT_OF_MEMORY and the records stay well formed: counts and extents as
 * ever, no pairs, each tile with a non-occluded fragment overflowed.
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
 *   out-of-memory-records-well-formed
 *       64 tiles each declaring 2^31 - 1 words (reserved address space, not
 *       memory): OUT_OF_MEMORY from RenderMode, NOHC exact, word 8 the
 *       terminator, the overflow count 1 for the one tile drawn into.
 */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS, MAP_NORESERVE */
#include <sys/mman.h>

#include "ou_util.h"

#define W 32
#define H 32

static GLuint buffer[8 + 2 * 300];

int main(int argc, char **argv)
{
    ou_init(argc, argv, W, H);
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

    /* 64 tiles of 2^31 - 1 words each: 512 GiB of address space, reserved
     * without memory; the GL's own copies of such lists cannot be had. */
    const size_t words = 0x7fffffffu;
    GLuint *huge = mmap(NULL, 64 * words * sizeof(GLuint), PROT_READ | PROT_WRITE,
                        MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (huge == MAP_FAILED) {
        printf("could not reserve 512 GiB of address space\n");
        subtest(false, "out-of-memory-records-well-formed");
        piglit_report_result(result);
    }
    GLuint *many[64];
    GLsizei many_sizes[64];
    GLint tiles[64 * 4];
    for (int k = 0; k < 64; ++k) {
        many[k] = huge + (size_t)k * words;
        many_sizes[k] = (GLsizei)words;
        ou_fill(many[k], 16);
        tiles[4 * k] = k % 8 * 4;
        tiles[4 * k + 1] = k / 8 * 4;
        tiles[4 * k + 2] = 4;
        tiles[4 * k + 3] = 4;
    }
    OcclusionBuffersMESAX(64, many_sizes, many);
    ScissorsMESAX(64, tiles);
    while (glGetError() != GL_NO_ERROR)
        ;
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    GLenum error = glGetError();
    ou_rect(0, 0, 2, 2, 0.5f);   /* 4 fragments, all in tile 0 */
    const GLint n = glRenderMode(GL_RENDER);
    if (error == GL_NO_ERROR)
        error = glGetError();
    ScissorsMESAX(0, NULL);
    const bool oom = error == GL_OUT_OF_MEMORY && n == 1 && many[0][OU_NOHC] == 4 && many[0][OU_PHC] == 4 &&
                     many[0][8] == 0xffffffffu && many[1][OU_NOHC] == 0;
    if (!oom)
        printf("out of memory: error 0x%x, returned %d, NOHC %u, word 8 0x%08x\n", error, n, many[0][OU_NOHC],
               many[0][8]);
    subtest(oom, "out-of-memory-records-well-formed");
    munmap(huge, 64 * words * sizeof(GLuint));
    piglit_report_result(result);
}
