/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit, VERBOSE_OCCLUSION_MESAX: the memory a verbose
 * pass takes grows with the fragments it lists, not with the sizes the
 * application declares (section 5.X: a buffer may be declared with up to
 * 2^31 - 1 words, the GL writes only the record). The pairs a tile can
 * list in a pass that draws each pixel once are at most its area, so the
 * pass is held to a bound derived from the tiles' areas.
 *
 * Bound: 32 bytes for each pixel of the tiles (a pair is kept as one
 * 8-byte key; a list's memory at most doubles its pairs as it grows, and
 * llvmpipe's merge of its rasterizer threads' lists copies them once more:
 * 8 * 2 + 8 = 24 bytes, rounded up) plus 4 MiB for the pass's fixed
 * structures, measured from just before RenderMode enters the mode to
 * just after it leaves it, after a warm-up pass of the same draw (so that
 * shaders and scene memory already exist), as
 *   - the growth of the process's peak address space (VmPeak of
 *     /proc/self/status): what strict overcommit would charge, and
 *   - the growth of its peak resident set (getrusage's ru_maxrss).
 * glibc's malloc is limited to one arena (mallopt M_ARENA_MAX) so that the
 * rasterizer threads' first allocations do not reserve 64 MiB arenas of
 * their own, which would be the allocator's cost, not the GL's.
 *
 * Subtests (128 x 128 window, one full-window quad, depth test off):
 *   one-tile-of-2^31-1-words
 *       one tile over the window (16384 pixels) with a buffer of
 *       2^31 - 1 words (8 GiB, reserved without memory by the test):
 *       NOHC, PHC and extents exact, the list every pixel once, no
 *       overflow, no error; memory within 32 * 16384 bytes + 4 MiB.
 *   sixty-four-tiles-of-2^31-1-words
 *       64 tiles of 16 x 16 (together the window), each with a buffer of
 *       2^31 - 1 words (512 GiB declared): every record exact as above;
 *       memory within 32 * 16384 bytes + 4 MiB.
 */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS, MAP_NORESERVE */
#include <inttypes.h>
#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>

#include "ou_util.h"

#define W 128
#define H 128
#define HUGE_WORDS 0x7fffffffu
#define BYTES_PER_PIXEL 32u
#define FIXED_BYTES (4u << 20)

/* VmPeak of /proc/self/status, in bytes; 0 when it cannot be read. */
static uint64_t
peak_address_space(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    uint64_t kib = 0;
    if (!f)
        return 0;
    while (fgets(line, sizeof(line), f))
        if (sscanf(line, "VmPeak: %" SCNu64 " kB", &kib) == 1)
            break;
    fclose(f);
    return kib * 1024;
}

static uint64_t
peak_resident(void)
{
    struct rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    return (uint64_t)usage.ru_maxrss * 1024;
}

static void
draw_window(void)
{
    ou_rect(0, 0, W, H, 0.5f);
}

/* One verbose pass over the window, tiles `grid` x `grid`, into `buffers`. */
static GLint
verbose_pass(int grid, GLuint **buffers, GLsizei *sizes)
{
    GLint tiles[64 * 4];
    const int n = grid * grid, side = W / grid;
    for (int k = 0; k < n; ++k) {
        tiles[4 * k] = k % grid * side;
        tiles[4 * k + 1] = k / grid * side;
        tiles[4 * k + 2] = side;
        tiles[4 * k + 3] = side;
        ou_fill(buffers[k], 8 + 2 * side * side + 1);
    }
    OcclusionBuffersMESAX(n, sizes, buffers);
    ScissorsMESAX(n, tiles);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_window();
    const GLint overflowed = glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    return overflowed;
}

/* Tile k of a grid: its record exact, its list every pixel once. */
static bool
check_tile(int grid, int k, const GLuint *record)
{
    const int side = W / grid, x0 = k % grid * side, y0 = k / grid * side;
    const GLuint area = (GLuint)(side * side);
    const GLuint expected[OU_BRIEF_SIZE] = {area,          area,          (GLuint)x0,     (GLuint)(x0 + side - 1),
                                            (GLuint)y0,    (GLuint)(y0 + side - 1), ou_depth(0.5), ou_depth(0.5)};
    char what[32];
    snprintf(what, sizeof(what), "tile %d", k);
    bool ok = ou_check_record(what, record, expected, 1);
    static bool seen[W * H];
    memset(seen, 0, sizeof(seen));
    for (GLuint i = 0; ok && i < area; ++i) {
        const GLuint x = record[8 + 2 * i], y = record[8 + 2 * i + 1];
        const bool inside = x >= (GLuint)x0 && x < (GLuint)(x0 + side) && y >= (GLuint)y0 && y < (GLuint)(y0 + side);
        if (!inside || seen[y * W + x]) {
            printf("%s: pair %u is (%u, %u): %s\n", what, i, x, y, inside ? "listed twice" : "outside the tile");
            ok = false;
        } else {
            seen[y * W + x] = true;
        }
    }
    if (ok && record[8 + 2 * area] != OU_SENTINEL) {
        printf("%s: word %u after the list is 0x%08x, not the application's\n", what, 8 + 2 * area,
               record[8 + 2 * area]);
        ok = false;
    }
    return ok;
}

static void
huge_declarations(int grid, const char *name)
{
    const int n = grid * grid, side = W / grid;
    const size_t small_words = 8 + 2 * (size_t)side * side + 1;
    GLuint *buffers[64];
    GLsizei sizes[64];

    /* The application's buffers: HUGE_WORDS each, reserved without memory;
     * the GL writes only the records (8 + 2 * area words each). */
    const size_t bytes = (size_t)n * HUGE_WORDS * sizeof(GLuint);
    GLuint *huge = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    GLuint *small = malloc((size_t)n * small_words * sizeof(GLuint));
    if (huge == MAP_FAILED || !small) {
        printf("%s: could not reserve %zu bytes of address space\n", name, bytes);
        subtest(false, name);
        return;
    }

    /* Warm-up: the same pass with buffers just large enough. */
    for (int k = 0; k < n; ++k) {
        buffers[k] = small + (size_t)k * small_words;
        sizes[k] = (GLsizei)small_words;
    }
    GLint overflowed = verbose_pass(grid, buffers, sizes);
    bool ok = overflowed == 0 && glGetError() == GL_NO_ERROR;
    for (int k = 0; ok && k < n; ++k)
        ok = check_tile(grid, k, buffers[k]);
    if (!ok)
        printf("%s: the warm-up pass with buffers that fit is wrong (returned %d)\n", name, overflowed);

    for (int k = 0; k < n; ++k) {
        buffers[k] = huge + (size_t)k * HUGE_WORDS;
        sizes[k] = (GLsizei)HUGE_WORDS;
    }
    const uint64_t address_space_before = peak_address_space(), resident_before = peak_resident();
    overflowed = verbose_pass(grid, buffers, sizes);
    const uint64_t address_space_after = peak_address_space(), resident_after = peak_resident();
    const GLenum error = glGetError();

    const uint64_t bound = (uint64_t)BYTES_PER_PIXEL * W * H + FIXED_BYTES;
    const uint64_t address_space = address_space_after - address_space_before;
    const uint64_t resident = resident_after - resident_before;
    printf("%s: %d tile(s) of %d x %d declaring %u words each: peak address space grew by %" PRIu64
           " bytes, peak resident set by %" PRIu64 " bytes; bound %" PRIu64 " bytes\n",
           name, n, side, side, HUGE_WORDS, address_space, resident, bound);
    if (!address_space_before) {
        printf("%s: /proc/self/status has no VmPeak\n", name);
        ok = false;
    }
    if (address_space > bound || resident > bound)
        ok = false;
    if (overflowed != 0 || error != GL_NO_ERROR) {
        printf("%s: RenderMode returned %d, error 0x%x (0 and none expected)\n", name, overflowed, error);
        ok = false;
    }
    for (int k = 0; k < n; ++k)
        ok = check_tile(grid, k, buffers[k]) && ok;
    subtest(ok, name);
    munmap(huge, bytes);
    free(small);
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
    /* One arena: see the comment at the top. */
    mallopt(M_ARENA_MAX, 1);
    ou_init();
    glDisable(GL_DEPTH_TEST);

    huge_declarations(1, "one-tile-of-2^31-1-words");
    huge_declarations(8, "sixty-four-tiles-of-2^31-1-words");
    piglit_report_result(result);
}
