/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_conservative: a conservative pass never answers
 * 0 for a tile where GL_RENDER's SAMPLES_PASSED counts a sample
 * (spec, section 5.X: "it never answers 0 where one did").
 *
 * Seeded random scenes on a 203 x 150 window (bins cut by its edge):
 * occluders drawn in GL_RENDER over a random clear depth, then a pass of
 * random triangles (some covering many 64x64 bins, some inside one 16x16
 * block) under each depth function, with polygon offset and depth
 * clamping, over tiles of 1x1 pixel, straddling bins, overlapping and the
 * whole window. The reference for each tile is an ARB_occlusion_query of
 * the same triangles in GL_RENDER, scissored to the tile, with depth
 * writes off as in the pass. The test runs at every LP_NUM_THREADS the
 * build registers, where threads mark tiles passed for each other.
 *
 * Subtests:
 *   never-none-where-samples-passed  the contract;
 *   record-is-one-word               word 0 is 0 or 1, words 1-7 of each
 *                                    buffer keep the application's values,
 *                                    RenderMode returns 0;
 *   hidden-tiles-answered-none       where no sample passed the record is
 *                                    0: the spec allows 1, but softpipe
 *                                    answers exactly and llvmpipe drops
 *                                    only work that cannot change an
 *                                    answer (a primitive no fragment of
 *                                    which can pass in a bin, or a bin
 *                                    whose tiles have all passed), so a 1
 *                                    there is a defect of this
 *                                    implementation, and without this
 *                                    check "1 everywhere" would pass.
 */
#include "ou_util.h"

#include <math.h>

#define W 203
#define H 150
#define SCENES 60
#define TILES 12
#define MAX_TRIS 10
#define SENTINEL 0x5a5a5a5au

static unsigned seed = 1;

static float
rnd(void)
{
    seed = seed * 1103515245u + 12345u;
    return (float)((seed >> 8) & 0xffff) / 65535.0f;
}

static int
rndi(int n)
{
    return (int)(rnd() * (float)n * 0.99999f);
}

static float tri[MAX_TRIS][3][3];
static int num_tris;

static void
draw_tris(void)
{
    glBegin(GL_TRIANGLES);
    for (int i = 0; i < num_tris; ++i)
        for (int v = 0; v < 3; ++v)
            glVertex3fv(tri[i][v]);
    glEnd();
}

/* A triangle over much of the window, one inside a 16x16 block, or one of
 * a few pixels; z in [-0.2, 1.2] so that depth clamping has work. */
static void
random_triangle(float t[3][3])
{
    const int kind = rndi(3);
    const float size = kind == 0 ? 2.0f * W : kind == 1 ? 14.0f : 3.0f;
    const float cx = rnd() * W, cy = rnd() * H, z = rnd() * 1.4f - 0.2f;
    for (int v = 0; v < 3; ++v) {
        t[v][0] = cx + (rnd() - 0.5f) * size;
        t[v][1] = cy + (rnd() - 0.5f) * size;
        t[v][2] = z + (rnd() - 0.5f) * (kind == 0 ? 0.8f : 0.1f);
    }
}

static void
random_tiles(GLint *tiles)
{
    for (int i = 0; i < TILES; ++i) {
        GLint *t = tiles + 4 * i;
        switch (rndi(4)) {
        case 0: /* one pixel, often on a bin corner */
            t[0] = rnd() < 0.5f ? 64 * rndi(4) - rndi(2) : rndi(W);
            t[1] = rnd() < 0.5f ? 64 * rndi(3) - rndi(2) : rndi(H);
            t[2] = t[3] = 1;
            break;
        case 1: /* straddling bins */
            t[0] = rndi(W) - 20;
            t[1] = rndi(H) - 20;
            t[2] = 30 + rndi(90);
            t[3] = 30 + rndi(90);
            break;
        case 2: /* the whole window */
            t[0] = t[1] = 0;
            t[2] = W;
            t[3] = H;
            break;
        default: /* a bin exactly */
            t[0] = 64 * rndi(4);
            t[1] = 64 * rndi(3);
            t[2] = t[3] = 64;
            break;
        }
        if (t[0] < 0)
            t[0] = 0;
        if (t[1] < 0)
            t[1] = 0;
    }
}

static const GLenum funcs[8] = {GL_NEVER, GL_LESS, GL_EQUAL, GL_LEQUAL,
                                GL_GREATER, GL_NOTEQUAL, GL_GEQUAL, GL_ALWAYS};

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
    ou_require_conservative();
    piglit_require_extension("GL_ARB_occlusion_query");
    const bool has_clamp = piglit_is_extension_supported("GL_ARB_depth_clamp");
    PFNGLGENQUERIESPROC GenQueries = glGenQueries;
    PFNGLBEGINQUERYPROC BeginQuery = glBeginQuery;
    PFNGLENDQUERYPROC EndQuery = glEndQuery;
    PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv =
        glGetQueryObjectuiv;
    GLuint query;
    GenQueries(1, &query);

    bool never_none = true, one_word = true, exact = true;
    int passed_tiles = 0, hidden_tiles = 0;
    static GLuint records[TILES][OU_BRIEF_SIZE];
    GLuint *buffers[TILES];
    GLsizei sizes[TILES];
    GLint tiles[4 * TILES];

    glEnable(GL_DEPTH_TEST);
    for (int scene = 0; scene < SCENES; ++scene) {
        /* The occluders, drawn. */
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_POLYGON_OFFSET_FILL);
        if (has_clamp)
            glDisable(GL_DEPTH_CLAMP);
        glDepthMask(GL_TRUE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthFunc(GL_LESS);
        glClearDepth(0.3 + 0.7 * rnd());
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        num_tris = 1 + rndi(6);
        for (int i = 0; i < num_tris; ++i)
            random_triangle(tri[i]);
        draw_tris();

        /* The pass's state and triangles. */
        const GLenum func = funcs[rndi(8)];
        glDepthFunc(func);
        const bool offset = rnd() < 0.25f, clamp = has_clamp && rnd() < 0.25f;
        if (offset) {
            glEnable(GL_POLYGON_OFFSET_FILL);
            glPolygonOffset(rnd() * 4.0f - 2.0f, rnd() * 200.0f - 100.0f);
        }
        if (clamp)
            glEnable(GL_DEPTH_CLAMP);
        num_tris = 1 + rndi(MAX_TRIS);
        for (int i = 0; i < num_tris; ++i)
            random_triangle(tri[i]);
        random_tiles(tiles);

        for (int i = 0; i < TILES; ++i) {
            for (int w = 0; w < OU_BRIEF_SIZE; ++w)
                records[i][w] = SENTINEL;
            buffers[i] = records[i];
            sizes[i] = OU_BRIEF_SIZE;
        }
        OcclusionBuffersMESAX(TILES, sizes, buffers);
        ScissorsMESAX(TILES, tiles);
        glRenderMode(GL_CONSERVATIVE_OCCLUSION_MESAX);
        draw_tris();
        const GLint returned = glRenderMode(GL_RENDER);
        ScissorsMESAX(0, NULL);
        if (returned != 0 || !piglit_check_gl_error(GL_NO_ERROR)) {
            printf("scene %d: RenderMode returned %d leaving the mode\n", scene, returned);
            one_word = false;
        }

        /* The reference: each tile's samples in GL_RENDER, nothing written. */
        glDepthMask(GL_FALSE);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glEnable(GL_SCISSOR_TEST);
        for (int i = 0; i < TILES; ++i) {
            const GLint *t = tiles + 4 * i;
            glScissor(t[0], t[1], t[2], t[3]);
            BeginQuery(GL_SAMPLES_PASSED, query);
            draw_tris();
            EndQuery(GL_SAMPLES_PASSED);
            GLuint samples = 0;
            GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);

            const GLuint answer = records[i][0];
            if (answer > 1) {
                printf("scene %d tile %d: word 0 is %#x, not 0 or 1\n", scene, i, answer);
                one_word = false;
            }
            for (int w = 1; w < OU_BRIEF_SIZE; ++w) {
                if (records[i][w] != SENTINEL) {
                    printf("scene %d tile %d: word %d changed to %#x\n", scene, i, w, records[i][w]);
                    one_word = false;
                }
            }
            if (samples > 0) {
                passed_tiles++;
                if (answer == 0) {
                    printf("scene %d tile %d (%d %d %d %d, depth function %#x%s%s): answered 0, "
                           "but %u samples passed\n", scene, i, t[0], t[1], t[2], t[3], func,
                           offset ? ", polygon offset" : "", clamp ? ", depth clamp" : "", samples);
                    never_none = false;
                }
            } else {
                hidden_tiles++;
                if (answer != 0) {
                    printf("scene %d tile %d (%d %d %d %d, depth function %#x): answered %u, "
                           "no sample passed\n", scene, i, t[0], t[1], t[2], t[3], func, answer);
                    exact = false;
                }
            }
        }
    }
    printf("%d tiles with samples passing, %d without\n", passed_tiles, hidden_tiles);
    /* Both kinds must occur, or the scenes test nothing. */
    if (passed_tiles == 0 || hidden_tiles == 0)
        never_none = exact = false;

    subtest(never_none, "never-none-where-samples-passed");
    subtest(one_word, "record-is-one-word");
    subtest(exact, "hidden-tiles-answered-none");
    piglit_report_result(result);
}
