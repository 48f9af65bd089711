/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit with 4096 tiles, which softpipe and llvmpipe
 * report (an implementation's limit; the spec's minimum is 64): a 64 x 64
 * grid of tiles, and tiles overlapping 1 to 4 deep, over boxes in front of
 * and behind a depth-buffered background, every record against counts
 * computed from the boxes' pixels.
 *
 * Subtests:
 *   max-tiles-at-least-4096          MAX_OCCLUSION_TILES_MESAX >= 4096
 *   grid-brief                       64 x 64 disjoint tiles, RenderMode's records
 *   overlapping-brief                tile (i, j) spans 1 or 2 tile widths and
 *                                    heights: each pixel lies in 1 to 4 tiles
 *   overlapping-verbose              the same, each tile's list holding exactly
 *                                    its visible pixels (a pair per fragment)
 *   conditional-render-tile-4095     a pass object's last tile decides a draw,
 *                                    its neighbour 4094 (nothing visible) not
 *   query-buffer-4096-records        the pass's 4096 records read into a buffer
 *                                    bound to QUERY_BUFFER equal those read
 *                                    into client memory
 *
 * The tiles are S x S pixels, S = 8 on llvmpipe (512 x 512, so that a 64 x 64
 * bin holds 64 tiles, and the boxes cross bins, blocks and tiles), S = 1 on
 * softpipe (64 x 64), which visits every tile for every quad.
 *
 * Tolerances: counts, coordinates and depth exact: the boxes' z (0.125, 0.25,
 * 0.75) and the background's 0.5 are exact in float32 and through ou_init's
 * transforms, and pixel centres are never on a box edge.
 */
#include "ou_util.h"

#define N 64   /* tiles per row and column */
#define MIN2(a, b) ((a) < (b) ? (a) : (b))
#define MAX2(a, b) ((a) > (b) ? (a) : (b))
#define TILES (N * N)

static int S, W;   /* tile size, window size (W = N * S) */
static struct ou_async_functions a;

struct box { int x0, y0, x1, y1; float z; };
static struct box boxes[3];
static const float BACKGROUND_Z = 0.5f;

static void
draw_boxes(void)
{
    for (int b = 0; b < 3; ++b)
        ou_rect(boxes[b].x0, boxes[b].y0, boxes[b].x1, boxes[b].y1, boxes[b].z);
}

/* Tile k of a layout, as ScissorsMESAX takes it. */
static void
grid_tiles(GLint *t)
{
    for (int k = 0; k < TILES; ++k) {
        t[4 * k] = (k % N) * S;
        t[4 * k + 1] = (k / N) * S;
        t[4 * k + 2] = S;
        t[4 * k + 3] = S;
    }
}

static void
overlapping_tiles(GLint *t)
{
    for (int k = 0; k < TILES; ++k) {
        const int i = k % N, j = k / N;
        t[4 * k] = i * S;
        t[4 * k + 1] = j * S;
        t[4 * k + 2] = S * (1 + (i & 1));
        t[4 * k + 3] = S * (1 + (j & 1));
    }
}

/* The record tile `t` must hold: the boxes' fragments inside it (and the
 * window), the visible ones those in front of the background. */
static void
expected_record(const GLint *t, GLuint r[OU_BRIEF_SIZE])
{
    const int tx0 = MAX2(t[0], 0), ty0 = MAX2(t[1], 0);
    const int tx1 = MIN2(t[0] + t[2], W), ty1 = MIN2(t[1] + t[3], W);
    const GLuint e = OU_EMPTY_MIN, o = OU_EMPTY_MAX;
    GLuint init[OU_BRIEF_SIZE] = {0, 0, e, o, e, o, e, o};
    memcpy(r, init, sizeof(init));
    for (int b = 0; b < 3; ++b) {
        const int x0 = MAX2(tx0, boxes[b].x0), x1 = MIN2(tx1, boxes[b].x1);
        const int y0 = MAX2(ty0, boxes[b].y0), y1 = MIN2(ty1, boxes[b].y1);
        if (x0 >= x1 || y0 >= y1)
            continue;
        const GLuint area = (GLuint)((x1 - x0) * (y1 - y0));
        r[OU_PHC] += area;
        if (boxes[b].z >= BACKGROUND_Z)
            continue;
        r[OU_NOHC] += area;
        r[OU_XMIN] = MIN2(r[OU_XMIN], (GLuint)x0);
        r[OU_XMAX] = MAX2(r[OU_XMAX], (GLuint)x1 - 1);
        r[OU_YMIN] = MIN2(r[OU_YMIN], (GLuint)y0);
        r[OU_YMAX] = MAX2(r[OU_YMAX], (GLuint)y1 - 1);
        r[OU_ZMIN] = MIN2(r[OU_ZMIN], ou_depth(boxes[b].z));
        r[OU_ZMAX] = MAX2(r[OU_ZMAX], ou_depth(boxes[b].z));
    }
}

/* The visible pixels of the boxes inside tile `t`, a pair per fragment;
 * returns their number. */
static size_t
expected_pairs(const GLint *t, GLuint *pairs)
{
    const int tx0 = MAX2(t[0], 0), ty0 = MAX2(t[1], 0);
    const int tx1 = MIN2(t[0] + t[2], W), ty1 = MIN2(t[1] + t[3], W);
    size_t n = 0;
    for (int b = 0; b < 3; ++b) {
        if (boxes[b].z >= BACKGROUND_Z)
            continue;
        for (int y = MAX2(ty0, boxes[b].y0); y < MIN2(ty1, boxes[b].y1); ++y)
            for (int x = MAX2(tx0, boxes[b].x0); x < MIN2(tx1, boxes[b].x1); ++x) {
                pairs[2 * n] = x;
                pairs[2 * n + 1] = y;
                ++n;
            }
    }
    ou_sort_pairs(pairs, n);
    return n;
}

/* The background's depth, then the tiles and one buffer of `size[k]` words
 * per tile. */
static void
set_up(const GLint *tiles, GLuint **buffers, const GLsizei *sizes)
{
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    ou_rect(0, 0, W, W, BACKGROUND_Z);
    OcclusionBuffersMESAX(TILES, sizes, buffers);
    ScissorsMESAX(TILES, tiles);
}

static bool
check_brief(const char *layout, const GLint *tiles, GLuint **records)
{
    bool ok = true;
    int bad = 0;
    for (int k = 0; k < TILES && bad < 5; ++k) {
        GLuint expected[OU_BRIEF_SIZE];
        expected_record(&tiles[4 * k], expected);
        char what[64];
        snprintf(what, sizeof(what), "%s tile %d", layout, k);
        if (!ou_check_record(what, records[k], expected, 0)) {
            ok = false;
            ++bad;
        }
    }
    return ok;
}

/* A brief pass through RenderMode over a layout. */
static void
brief_subtest(const char *name, void (*layout)(GLint *), GLint *tiles, GLuint **buffers, GLsizei *sizes)
{
    layout(tiles);
    for (int k = 0; k < TILES; ++k) {
        sizes[k] = OU_BRIEF_SIZE;
        ou_fill(buffers[k], OU_BRIEF_SIZE);
    }
    set_up(tiles, buffers, sizes);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    draw_boxes();
    const GLint overflowed = glRenderMode(GL_RENDER);
    bool ok = piglit_check_gl_error(GL_NO_ERROR) && overflowed == 0;
    if (ok)
        ok = check_brief(name, tiles, buffers);
    subtest(ok, name);
}

static void
verbose_subtest(GLint *tiles, GLuint **buffers, GLsizei *sizes, GLuint *pairs)
{
    overlapping_tiles(tiles);
    for (int k = 0; k < TILES; ++k) {
        GLuint expected[OU_BRIEF_SIZE];
        expected_record(&tiles[4 * k], expected);
        /* Room for every pair, and one word the GL must leave alone. */
        sizes[k] = OU_BRIEF_SIZE + 2 * expected[OU_NOHC] + 1;
        buffers[k] = realloc(buffers[k], 4 * sizes[k]);
        ou_fill(buffers[k], sizes[k]);
    }
    set_up(tiles, buffers, sizes);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_boxes();
    const GLint overflowed = glRenderMode(GL_RENDER);
    bool ok = piglit_check_gl_error(GL_NO_ERROR) && overflowed == 0;
    if (overflowed != 0)
        printf("overlapping-verbose: %d lists overflowed, expected 0\n", overflowed);
    if (ok)
        ok = check_brief("overlapping-verbose", tiles, buffers);
    int bad = 0;
    for (int k = 0; k < TILES && ok && bad < 5; ++k) {
        const size_t n = expected_pairs(&tiles[4 * k], pairs);
        GLuint *list = buffers[k] + OU_BRIEF_SIZE;
        ou_sort_pairs(list, n);
        if (memcmp(list, pairs, 8 * n) != 0 || list[2 * n] != OU_SENTINEL) {
            printf("overlapping-verbose: tile %d's list is not its %zu visible pixels\n", k, n);
            ok = false;
            ++bad;
        }
    }
    subtest(ok, "overlapping-verbose");
    for (int k = 0; k < TILES; ++k) {
        buffers[k] = realloc(buffers[k], 4 * OU_BRIEF_SIZE);
        sizes[k] = OU_BRIEF_SIZE;
    }
}

/* Clears to black, draws red under tile `tile`'s condition; true when drawn. */
static bool
drawn_under(GLuint pass, GLuint tile)
{
    glDisable(GL_DEPTH_TEST);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    a.BeginConditionalRenderOcclusionTile(pass, tile, 0, 0.0f, GL_QUERY_WAIT);
    glColor4ub(255, 0, 0, 255);
    ou_rect(0, 0, W, W, 0.5f);
    a.EndConditionalRenderOcclusionTile();
    unsigned char pixel[4];
    glReadPixels(W / 2, W / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel);
    return pixel[0] == 255;
}

/* A pass object over the grid with one visible box, in the last tile. */
static void
async_subtests(GLint *tiles, GLuint **buffers, GLsizei *sizes)
{
    grid_tiles(tiles);
    for (int k = 0; k < TILES; ++k)
        ou_fill(buffers[k], OU_BRIEF_SIZE);
    set_up(tiles, buffers, sizes);
    GLuint pass;
    a.GenOcclusionPasses(1, &pass);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    ou_rect(W - S, W - S, W, W, 0.25f);     /* tile 4095, in front */
    ou_rect(W - 2 * S, W - S, W - S, W, 0.75f);   /* tile 4094, behind */
    a.EndOcclusionPass();
    ScissorsMESAX(0, NULL);
    bool ok = piglit_check_gl_error(GL_NO_ERROR);
    const bool last = drawn_under(pass, TILES - 1), before = drawn_under(pass, TILES - 2);
    if (!last || before)
        printf("conditional-render-tile-4095: tile 4095 %s, tile 4094 %s (expected drawn, skipped)\n",
               last ? "drawn" : "skipped", before ? "drawn" : "skipped");
    subtest(ok && piglit_check_gl_error(GL_NO_ERROR) && last && !before, "conditional-render-tile-4095");

    /* The records in client memory: the reference for the query buffer. */
    GLint overflowed = -1;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    ok = piglit_check_gl_error(GL_NO_ERROR) && overflowed == 0 && buffers[TILES - 1][OU_NOHC] == (GLuint)(S * S) &&
         buffers[TILES - 2][OU_NOHC] == 0 && buffers[TILES - 2][OU_PHC] == (GLuint)(S * S);
    if (!ok)
        printf("pass object: tile 4095 NOHC %u, tile 4094 NOHC %u PHC %u (expected %d, 0, %d)\n",
               buffers[TILES - 1][OU_NOHC], buffers[TILES - 2][OU_NOHC], buffers[TILES - 2][OU_PHC], S * S, S * S);

    if (!piglit_is_extension_supported("GL_ARB_query_buffer_object")) {
        ou_subtest_dependency_missing("query-buffer-4096-records", "GL_ARB_query_buffer_object");
    } else {
        PFNGLGENBUFFERSPROC GenBuffers = glGenBuffers;
        PFNGLBINDBUFFERPROC BindBuffer = glBindBuffer;
        PFNGLBUFFERDATAPROC BufferData = glBufferData;
        PFNGLGETBUFFERSUBDATAPROC GetBufferSubData =
            glGetBufferSubData;
        GLuint *back = malloc(4 * TILES * OU_BRIEF_SIZE), buffer;
        ou_fill(back, TILES * OU_BRIEF_SIZE);
        GenBuffers(1, &buffer);
        BindBuffer(GL_QUERY_BUFFER, buffer);
        BufferData(GL_QUERY_BUFFER, 4 * TILES * OU_BRIEF_SIZE, back, GL_DYNAMIC_COPY);
        a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, (GLint *)(intptr_t)0);
        ok = piglit_check_gl_error(GL_NO_ERROR) && ok;
        GetBufferSubData(GL_QUERY_BUFFER, 0, 4 * TILES * OU_BRIEF_SIZE, back);
        BindBuffer(GL_QUERY_BUFFER, 0);
        for (int k = 0; k < TILES && ok; ++k)
            if (memcmp(back + k * OU_BRIEF_SIZE, buffers[k], 4 * OU_BRIEF_SIZE) != 0) {
                printf("query-buffer-4096-records: tile %d's record differs from client memory's\n", k);
                ok = false;
            }
        subtest(ok, "query-buffer-4096-records");
        free(back);
    }
    a.DeleteOcclusionPasses(1, &pass);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    /* The window's size depends on the driver (piglit_init checks that the
     * context's renderer is the one named). */
    const char *driver = getenv("GALLIUM_DRIVER");
    S = driver && strcmp(driver, "softpipe") == 0 ? 1 : 8;
    W = N * S;
    config.supports_gl_compat_version = 10;
    config.window_width = W;
    config.window_height = W;
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
    const char *driver = getenv("GALLIUM_DRIVER");
    a = ou_init_async();
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    if ((S == 1) != (strstr(renderer, "softpipe") != NULL)) {
        printf("GALLIUM_DRIVER %s, but the renderer is %s\n", driver ? driver : "(unset)", renderer);
        piglit_report_result(PIGLIT_FAIL);
    }

    const GLint max_tiles = ou_get_integer(GL_MAX_OCCLUSION_TILES_MESAX);
    if (max_tiles < TILES && !ou_driver_is_patched()) {
        printf("%s has %d tiles: the spec's minimum is 64\n", renderer, max_tiles);
        piglit_report_result(PIGLIT_SKIP);
    }
    if (max_tiles < TILES)
        printf("MAX_OCCLUSION_TILES_MESAX is %d\n", max_tiles);
    subtest(max_tiles >= TILES, "max-tiles-at-least-4096");

    /* Boxes crossing tiles, 4x4 blocks and 64x64 bins at odd offsets: two
     * in front of the background (one overlapping the hidden one), one
     * behind it. */
    boxes[0] = (struct box){W * 3 / 16 + 1, W / 8 + 3, W * 11 / 16 - 2, W * 5 / 8 + 1, 0.25f};
    boxes[1] = (struct box){W / 2 - 5, W / 4 + 2, W - 3, W * 7 / 8, 0.75f};
    boxes[2] = (struct box){0, W * 3 / 4, W / 4 + 1, W, 0.125f};

    GLint *tiles = malloc(sizeof(GLint) * 4 * TILES);
    GLuint **buffers = malloc(sizeof(GLuint *) * TILES);
    GLsizei *sizes = malloc(sizeof(GLsizei) * TILES);
    GLuint *pairs = malloc(sizeof(GLuint) * 2 * 4 * S * S * 3);
    for (int k = 0; k < TILES; ++k) {
        buffers[k] = malloc(4 * OU_BRIEF_SIZE);
        sizes[k] = OU_BRIEF_SIZE;
    }

    brief_subtest("grid-brief", grid_tiles, tiles, buffers, sizes);
    brief_subtest("overlapping-brief", overlapping_tiles, tiles, buffers, sizes);
    verbose_subtest(tiles, buffers, sizes, pairs);
    async_subtests(tiles, buffers, sizes);

    for (int k = 0; k < TILES; ++k)
        free(buffers[k]);
    free(buffers);
    free(sizes);
    free(tiles);
    free(pairs);
    piglit_report_result(result);
}
