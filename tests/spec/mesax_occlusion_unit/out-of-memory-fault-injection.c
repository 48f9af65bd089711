/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: OUT_OF_MEMORY (section 5.X and Errors) when the
 * driver's own allocations fail, not only the state tracker's. The patched
 * Mesa makes every allocation of an occlusion pass after its first N fail
 * when GALLIUM_OCCLUSION_FAIL_ALLOC_AFTER=N is in the environment as the
 * pass begins (util/u_occlusion_list.h): the state tracker's pass, the
 * driver's pass and, on llvmpipe, its per-thread engines and bin table, and
 * the verbose lists as they grow in the rasterizer threads and as they are
 * merged. The test sets N = 0, 1, 2, ... until passes succeed, and checks
 * that every pass ends in one of the three outcomes the spec allows:
 *   - not begun: RenderMode generates OUT_OF_MEMORY on entering and the
 *     render mode stays RENDER; leaving returns 0; no buffer is written;
 *   - lists lost: no error on entering, OUT_OF_MEMORY on leaving, which
 *     returns 1 (the one tile with non-occluded fragments overflowed);
 *     counts, extents and depth range exact; word 8 of that tile the
 *     terminator; the empty tile's record holds its header only;
 *   - whole: no error, RenderMode returns 0, every record and list exact.
 * After each pass a pass without fault injection must be whole (a failed
 * pass leaves nothing behind), and the process's allocated heap must be
 * the same after all the failed passes as after eight whole ones (within
 * 4 KiB; glibc's mallinfo2 with one arena, so that the rasterizer
 * threads' allocations are counted).
 *
 * Subtests (128 x 128 window; tile 0 the window, tile 1 a 16 x 16 square
 * the draw misses; a 64 x 32 quad, 2048 fragments over two 64 x 64 bins):
 *   pass-not-begun-reported
 *       some N leaves the pass unbegun, as described (the state tracker's
 *       and the driver's allocations at the start of the pass).
 *   lists-lost-reported
 *       some N loses the lists, as described (their growth or merge).
 *   every-outcome-allowed
 *       every pass for every N is one of the three outcomes, and the pass
 *       after it, without fault injection, is whole.
 *   no-memory-kept
 *       the heap in use after the failed passes is that after a whole one.
 *   tile-state-out-of-memory (with -tiles-4096)
 *       with allocations failing, ScissorsMESAX and OcclusionBuffersMESAX
 *       with MAX_OCCLUSION_TILES_MESAX entries (more than the 2 set, so
 *       the GL must grow its arrays) generate OUT_OF_MEMORY and leave the
 *       tiles and buffers set as they were (spec issue 26); without fault
 *       injection the same calls succeed.
 */
#define _DEFAULT_SOURCE /* setenv, unsetenv */
#include <malloc.h>

#include "ou_util.h"

#define W 128
#define H 128
#define PIXELS (64 * 32)
#define FAIL_AFTER "GALLIUM_OCCLUSION_FAIL_ALLOC_AFTER"
#define ARRAY_SIZE(a) ((GLsizei)(sizeof(a) / sizeof((a)[0])))

enum outcome { NOT_BEGUN, LISTS_LOST, WHOLE, WRONG };

static GLuint list0[8 + 2 * PIXELS + 1], list1[8 + 2 * 16 * 16 + 1];

static bool
untouched(const GLuint *buffer, int words)
{
    for (int i = 0; i < words; ++i)
        if (buffer[i] != OU_SENTINEL)
            return false;
    return true;
}

static bool
header_exact(const char *what)
{
    const GLuint expected0[OU_BRIEF_SIZE] = {PIXELS, PIXELS, 8, 71, 8, 39, ou_depth(0.5), ou_depth(0.5)};
    const GLuint expected1[OU_BRIEF_SIZE] = {0,           0,           OU_EMPTY_MIN, OU_EMPTY_MAX,
                                             OU_EMPTY_MIN, OU_EMPTY_MAX, OU_EMPTY_MIN, OU_EMPTY_MAX};
    bool ok = ou_check_record(what, list0, expected0, 1);
    ok = ou_check_record(what, list1, expected1, 0) && ok;
    if (list1[8] != OU_SENTINEL) {
        printf("%s: the empty tile's word 8 is 0x%08x\n", what, list1[8]);
        ok = false;
    }
    return ok;
}

static bool
list_exact(const char *what)
{
    static bool seen[64 * 32];
    memset(seen, 0, sizeof(seen));
    for (int i = 0; i < PIXELS; ++i) {
        const GLuint x = list0[8 + 2 * i], y = list0[8 + 2 * i + 1];
        if (x < 8 || x >= 72 || y < 8 || y >= 40 || seen[(y - 8) * 64 + (x - 8)]) {
            printf("%s: pair %d is (%u, %u)\n", what, i, x, y);
            return false;
        }
        seen[(y - 8) * 64 + (x - 8)] = true;
    }
    if (list0[8 + 2 * PIXELS] != OU_SENTINEL) {
        printf("%s: the word after the list is 0x%08x\n", what, list0[8 + 2 * PIXELS]);
        return false;
    }
    return true;
}

static enum outcome
verbose_pass(const char *what)
{
    GLuint *buffers[2] = {list0, list1};
    GLsizei sizes[2] = {ARRAY_SIZE(list0), ARRAY_SIZE(list1)};
    const GLint tiles[8] = {0, 0, W, H, 96, 96, 16, 16};
    ou_fill(list0, ARRAY_SIZE(list0));
    ou_fill(list1, ARRAY_SIZE(list1));
    OcclusionBuffersMESAX(2, sizes, buffers);
    ScissorsMESAX(2, tiles);
    while (glGetError() != GL_NO_ERROR)
        ;

    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    const GLenum entering = glGetError();
    GLint mode = 0;
    glGetIntegerv(GL_RENDER_MODE, &mode);
    ou_rect(8, 8, 72, 40, 0.5f);
    const GLint overflowed = glRenderMode(GL_RENDER);
    const GLenum leaving = glGetError();
    ScissorsMESAX(0, NULL);
    /* Nothing in flight when the next pass begins: a draw of a pass not
     * begun would otherwise still rasterize, and llvmpipe would take a
     * new scene (and keep its memory) for the next, which is no leak. */
    glFinish();

    if (entering == GL_OUT_OF_MEMORY) {
        if (mode == GL_RENDER && overflowed == 0 && leaving == GL_NO_ERROR &&
            untouched(list0, ARRAY_SIZE(list0)) && untouched(list1, ARRAY_SIZE(list1)))
            return NOT_BEGUN;
        printf("%s: not begun, but render mode 0x%x, RenderMode returned %d, error 0x%x on leaving, buffers %s\n",
               what, mode, overflowed, leaving,
               untouched(list0, ARRAY_SIZE(list0)) && untouched(list1, ARRAY_SIZE(list1)) ? "untouched" : "written");
        return WRONG;
    }
    if (entering != GL_NO_ERROR || mode != GL_VERBOSE_OCCLUSION_MESAX) {
        printf("%s: entering the mode gave error 0x%x, render mode 0x%x\n", what, entering, mode);
        return WRONG;
    }
    if (leaving == GL_OUT_OF_MEMORY) {
        const bool ok = header_exact(what) && overflowed == 1 && list0[8] == 0xffffffffu && list0[9] == OU_SENTINEL;
        if (!ok)
            printf("%s: lists lost, RenderMode returned %d, word 8 0x%08x, word 9 0x%08x\n", what, overflowed,
                   list0[8], list0[9]);
        return ok ? LISTS_LOST : WRONG;
    }
    if (leaving != GL_NO_ERROR || overflowed != 0) {
        printf("%s: leaving the mode gave error 0x%x and returned %d\n", what, leaving, overflowed);
        return WRONG;
    }
    return header_exact(what) && list_exact(what) ? WHOLE : WRONG;
}

/* The tile and buffer state as verbose_pass sets it, or not. */
static bool
two_tiles_set(const char *what)
{
    GLint tile0[4] = {-1, -1, -1, -1}, tile1[4] = {-1, -1, -1, -1};
    PFNGLGETINTEGERI_VPROC GetIntegeri_v = glGetIntegeri_v;
    GetIntegeri_v(GL_OCCLUSION_TILE_MESAX, 0, tile0);
    GetIntegeri_v(GL_OCCLUSION_TILE_MESAX, 1, tile1);
    GLint size1 = -1;
    GetIntegeri_v(GL_OCCLUSION_BUFFER_SIZE_MESAX, 1, &size1);
    const GLint tiles = ou_get_integer(GL_OCCLUSION_TILE_COUNT_MESAX);
    const GLint buffers = ou_get_integer(GL_OCCLUSION_BUFFER_COUNT_MESAX);
    const bool ok = tiles == 2 && buffers == 2 && tile0[2] == W && tile0[3] == H && tile1[0] == 96 &&
                    tile1[2] == 16 && size1 == ARRAY_SIZE(list1);
    if (!ok)
        printf("%s: %d tiles, %d buffers, tile 0 (%d, %d, %d, %d), tile 1 (%d, %d, %d, %d), buffer 1's size %d\n",
               what, tiles, buffers, tile0[0], tile0[1], tile0[2], tile0[3], tile1[0], tile1[1], tile1[2], tile1[3],
               size1);
    return ok;
}

static bool
tile_state_out_of_memory(void)
{
    const GLint max_tiles = ou_get_integer(GL_MAX_OCCLUSION_TILES_MESAX);
    GLint *tiles = malloc(sizeof(GLint) * 4 * max_tiles);
    GLuint **buffers = malloc(sizeof(GLuint *) * max_tiles);
    GLsizei *sizes = malloc(sizeof(GLsizei) * max_tiles);
    for (int k = 0; k < max_tiles; ++k) {
        const GLint t[4] = {k % W, k / W, 1, 1};
        memcpy(&tiles[4 * k], t, sizeof(t));
        buffers[k] = list0;
        sizes[k] = OU_BRIEF_SIZE;
    }
    const GLint two[8] = {0, 0, W, H, 96, 96, 16, 16};
    GLuint *two_buffers[2] = {list0, list1};
    GLsizei two_sizes[2] = {ARRAY_SIZE(list0), ARRAY_SIZE(list1)};
    ScissorsMESAX(2, two);
    OcclusionBuffersMESAX(2, two_sizes, two_buffers);

    /* A pass with every allocation failing is not begun, and arms the
     * fault injection for the allocations after it. */
    setenv(FAIL_AFTER, "0", 1);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    bool ok = ou_first_error() == GL_OUT_OF_MEMORY && ou_get_integer(GL_RENDER_MODE) == GL_RENDER;
    unsetenv(FAIL_AFTER);
    ScissorsMESAX(max_tiles, tiles);
    const GLenum scissors_error = ou_first_error();
    OcclusionBuffersMESAX(max_tiles, sizes, buffers);
    const GLenum buffers_error = ou_first_error();
    if (scissors_error != GL_OUT_OF_MEMORY || buffers_error != GL_OUT_OF_MEMORY) {
        printf("%d tiles and buffers with allocations failing: errors 0x%x and 0x%x, expected OUT_OF_MEMORY\n",
               max_tiles, scissors_error, buffers_error);
        ok = false;
    }
    ok = two_tiles_set("after OUT_OF_MEMORY") && ok;

    /* A pass without fault injection disarms it: the same calls succeed. */
    verbose_pass("disarming the fault injection");
    ScissorsMESAX(max_tiles, tiles);
    OcclusionBuffersMESAX(max_tiles, sizes, buffers);
    const bool set = piglit_check_gl_error(GL_NO_ERROR) && ou_get_integer(GL_OCCLUSION_TILE_COUNT_MESAX) == max_tiles &&
                     ou_get_integer(GL_OCCLUSION_BUFFER_COUNT_MESAX) == max_tiles;
    if (!set)
        printf("%d tiles and buffers without fault injection were not set\n", max_tiles);
    ScissorsMESAX(0, NULL);
    OcclusionBuffersMESAX(0, NULL, NULL);
    free(tiles);
    free(buffers);
    free(sizes);
    return ok && set;
}

static size_t
heap_in_use(void)
{
    const struct mallinfo2 info = mallinfo2();
    return info.uordblks + info.hblkhd;
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = W;
    config.window_height = H;
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
    /* One arena, so that mallinfo2 sees the rasterizer threads' memory. */
    mallopt(M_ARENA_MAX, 1);
    const bool tiles_4096 = ou_take_flag(&argc, argv, "-tiles-4096");
    ou_init();
    glDisable(GL_DEPTH_TEST);

    /* Passes without fault injection first, and the draw in RENDER mode
     * that a pass not begun makes, so that what the GL keeps from draw to
     * draw (compiled shaders, scenes) exists before the heap is measured. */
    unsetenv(FAIL_AFTER);
    bool allowed = true;
    for (int i = 0; i < 8; ++i) {
        allowed = verbose_pass("without fault injection") == WHOLE && allowed;
        ou_rect(8, 8, 72, 40, 0.5f);
        glFinish();
    }
    const size_t heap_before = heap_in_use();

    int not_begun = 0, lists_lost = 0, whole_in_a_row = 0;
    for (int n = 0; n < 200 && whole_in_a_row < 3; ++n) {
        char what[64], value[16];
        snprintf(value, sizeof(value), "%d", n);
        setenv(FAIL_AFTER, value, 1);
        snprintf(what, sizeof(what), FAIL_AFTER "=%d", n);
        const enum outcome o = verbose_pass(what);
        not_begun += o == NOT_BEGUN;
        lists_lost += o == LISTS_LOST;
        whole_in_a_row = o == WHOLE ? whole_in_a_row + 1 : 0;
        allowed = allowed && o != WRONG;

        unsetenv(FAIL_AFTER);
        snprintf(what, sizeof(what), "the pass after " FAIL_AFTER "=%d", n);
        allowed = verbose_pass(what) == WHOLE && allowed;
    }
    const size_t heap_after = heap_in_use();
    printf("passes not begun: %d, passes with lists lost: %d; heap in use %zu bytes before, %zu after\n",
           not_begun, lists_lost, heap_before, heap_after);

    subtest(not_begun > 0, "pass-not-begun-reported");
    subtest(lists_lost > 0, "lists-lost-reported");
    subtest(allowed, "every-outcome-allowed");
    subtest(heap_after <= heap_before + 4 * 1024, "no-memory-kept");
    if (tiles_4096)
        subtest(tile_state_out_of_memory(), "tile-state-out-of-memory");
    piglit_report_result(result);
}
