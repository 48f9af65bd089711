/*
 * GL_MESAX_occlusion_unit, VERBOSE_OCCLUSION_MESAX: the list of a tile is
 * exactly the set of pixels whose depth a GL_RENDER draw of the same
 * geometry changes; NOHC is its size; overflowed lists end in 0xFFFFFFFF
 * after as many whole pairs as fit, and glRenderMode returns the number of
 * overflowed tiles. No tolerance: sets are compared exactly.
 */
#include <stdlib.h>

#include "ou_util.h"

#define W 64
#define H 48



/* A tilted triangle in front of part of the occluder and behind another part. */
static void
draw_target(void)
{
    glBegin(GL_TRIANGLES);
    glVertex3f(3.3f, 2.7f, 0.2f);
    glVertex3f(60.1f, 11.4f, 0.6f);
    glVertex3f(21.8f, 45.2f, 0.45f);
    glEnd();
}

static void
setup_scene(void)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    ou_rect(20, 0, 44, 48, 0.4f);   /* occludes the triangle where it is deeper than 0.4 */
}

int main(int argc, char **argv)
{
    ou_init(argc, argv, W, H);
    const size_t n = (size_t)W * H;
    GLuint *before = malloc(n * 4), *after = malloc(n * 4);
    GLuint *expected = malloc(n * 2 * 4);
    GLuint *buffer = malloc((8 + 2 * n + 16) * 4);

    /* The reference: which pixels does a GL_RENDER draw change? */
    setup_scene();
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, before);
    draw_target();
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, after);
    size_t count = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            if (before[y * W + x] != after[y * W + x]) {
                expected[2 * count] = x;
                expected[2 * count + 1] = y;
                ++count;
            }

    /* The same in a verbose pass, with room for everything. */
    setup_scene();
    GLsizei size = (GLsizei)(8 + 2 * n);
    GLuint *buffers[1] = {buffer};
    ou_fill(buffer, (int)(8 + 2 * n + 16));
    OcclusionBuffersMESAX(1, &size, buffers);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_target();
    GLint overflowed = glRenderMode(GL_RENDER);
    GLuint nohc = buffer[OU_NOHC];
    bool ok = overflowed == 0 && nohc == count && count > 50 && piglit_check_gl_error(GL_NO_ERROR);
    if (!ok)
        printf("NOHC %u, pixels changed in GL_RENDER %zu, overflow %d\n", nohc, count, overflowed);
    subtest(ok, "nohc-equals-changed-pixels");

    bool same = nohc == count;
    if (same) {
        ou_sort_pairs(buffer + 8, nohc);
        same = memcmp(buffer + 8, expected, count * 2 * sizeof(GLuint)) == 0;
        if (!same)
            printf("the verbose list differs from the set of changed pixels\n");
    }
    subtest(same && buffer[8 + 2 * nohc] == OU_SENTINEL, "list-equals-changed-pixels");

    /* Exact fit: no terminator, the word after the buffer untouched. */
    setup_scene();
    size = (GLsizei)(8 + 2 * count);
    ou_fill(buffer, (int)(8 + 2 * n + 16));
    OcclusionBuffersMESAX(1, &size, buffers);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_target();
    overflowed = glRenderMode(GL_RENDER);
    subtest(overflowed == 0 && buffer[OU_NOHC] == count && buffer[size] == OU_SENTINEL &&
                buffer[size - 1] != 0xffffffffu,
            "exact-fit-no-overflow");

    /* Three tiles, two of them overflowing: one word short, and only 10 words. */
    GLuint *b1 = malloc((8 + 2 * n + 16) * 4), *b2 = malloc(64 * 4);
    GLuint *three[3] = {buffer, b1, b2};
    GLsizei sizes[3] = {(GLsizei)(8 + 2 * n), (GLsizei)(8 + 2 * count - 1), 10};
    const GLint tiles[12] = {0, 0, W, H, 0, 0, W, H, 0, 0, W, H};
    setup_scene();
    ou_fill(buffer, (int)(8 + 2 * n + 16));
    ou_fill(b1, (int)(8 + 2 * n + 16));
    ou_fill(b2, 64);
    OcclusionBuffersMESAX(3, sizes, three);
    ScissorsMESAX(3, tiles);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_target();
    overflowed = glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    const size_t k1 = (size_t)(sizes[1] - 9) / 2;   /* whole pairs before the terminator */
    subtest(overflowed == 2, "rendermode-returns-overflowed-tiles");
    subtest(b1[OU_NOHC] == count && b1[8 + 2 * k1] == 0xffffffffu && b1[8 + 2 * k1 - 1] != OU_SENTINEL &&
                b1[8 + 2 * k1 + 1] == OU_SENTINEL,
            "overflow-one-word-short-terminated");
    subtest(b2[OU_NOHC] == count && b2[8] == 0xffffffffu && b2[9] == OU_SENTINEL, "overflow-10-words-terminated");
    subtest(buffer[8 + 2 * count] == OU_SENTINEL && buffer[OU_NOHC] == count, "fitting-tile-not-terminated");

    /* A buffer of 8 words in verbose mode: the brief record, counted as overflowed. */
    setup_scene();
    GLsizei eight = 8;
    ou_fill(b2, 64);
    GLuint *only[1] = {b2};
    OcclusionBuffersMESAX(1, &eight, only);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_target();
    overflowed = glRenderMode(GL_RENDER);
    subtest(overflowed == 1 && b2[OU_NOHC] == count && b2[8] == OU_SENTINEL, "overflow-8-words-no-terminator");

    free(before); free(after); free(expected); free(buffer); free(b1); free(b2);
    piglit_report_result(result);
}
