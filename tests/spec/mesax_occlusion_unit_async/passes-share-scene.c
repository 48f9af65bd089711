/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: passes and draws issued with no Flush and
 * no read in between count in the order issued (spec MESAX_occlusion_unit,
 * section 5.X: a pass counts the fragments of its own primitives against
 * the depth buffer as the commands before it left it). An implementation
 * may keep them all in one batch of work (llvmpipe bins them into one
 * scene); each pass must still see the depth of the draws before it and
 * none after, and no pass's counts may leak into another's.
 *
 * 256 x 256 window, depth cleared to 1, LESS. With no Flush and no read:
 *   occluder A  RENDER, z 0.25 over columns 0-127
 *   pass P1     brief, the box (32,32)-(160,160) at z 0.5
 *   occluder B  RENDER, z 0.375 over (128,32)-(160,96)
 *   pass P2     brief, the same box
 *   draw C      RENDER, GREATER with depth writes, z 0.75 over the window:
 *               raises A's and B's depth to 0.75, leaves 1 elsewhere
 *   pass P3     verbose, LESS, the same box: all of it visible
 * Tiles of each pass: T0 (40,50) 60 x 30, inside the box and across the
 * bins at x 64 and y 64; T1 the pixel (130,100); T2 the window.
 * The records are read at the end and compared with counts of whole
 * pixels: P1 NOHC in T2 is 32 x 128 (B not yet drawn), P2's 32 x 64, P3's
 * 128 x 128, and P3's lists hold exactly its tiles' pixels. Depth is
 * exact: z 0.5 maps to itself (counts-analytic.c), record 0x80000000.
 *
 * Subtests:
 *   first-pass-sees-depth-before-it    P1's records
 *   second-pass-sees-occluder-between  P2's records
 *   verbose-pass-after-render-draw     P3's records and lists
 *   no-depth-buffer-then-opaque-draw   a colour-only framebuffer object, a
 *                                      pass over the window, then an opaque
 *                                      RENDER draw over the window, read
 *                                      after it: the pass counts its quad
 *
 * The test runs on llvmpipe with LP_NUM_THREADS 0, 1, 2 and 8 too
 * (tests/meson.build).
 */
#include "ou_util.h"

enum { S = 256, TILES = 3, LIST_WORDS = 8 + 2 * S * S };

static struct ou_async_functions a;
static const GLint tiles[4 * TILES] = {40, 50, 60, 30, 130, 100, 1, 1, 0, 0, S, S};
static GLuint brief[2][TILES][OU_BRIEF_SIZE];
static GLuint verbose[TILES][LIST_WORDS];

static void
begin_pass(GLuint pass, GLenum mode, GLuint *buffers[TILES], GLsizei size)
{
    GLsizei sizes[TILES];
    for (int i = 0; i < TILES; ++i) {
        ou_fill(buffers[i], size);
        sizes[i] = size;
    }
    OcclusionBuffersMESAX(TILES, sizes, buffers);
    ScissorsMESAX(TILES, tiles);
    a.BeginOcclusionPass(mode, pass);
}

static void
box(void)
{
    ou_rect(32, 32, 160, 160, 0.5f);
}

/* The record of `count` visible pixels of the box inside [x0, x1] x [y0, y1]
 * (count 0: empty extents) out of `phc`. */
static void
expect(GLuint r[OU_BRIEF_SIZE], GLuint phc, GLuint count, GLuint x0, GLuint x1, GLuint y0, GLuint y1)
{
    r[OU_PHC] = phc;
    r[OU_NOHC] = count;
    if (count) {
        r[OU_XMIN] = x0; r[OU_XMAX] = x1; r[OU_YMIN] = y0; r[OU_YMAX] = y1;
        r[OU_ZMIN] = r[OU_ZMAX] = ou_depth(0.5);
    } else {
        r[OU_XMIN] = r[OU_YMIN] = r[OU_ZMIN] = OU_EMPTY_MIN;
        r[OU_XMAX] = r[OU_YMAX] = r[OU_ZMAX] = OU_EMPTY_MAX;
    }
}

static bool
check_pass(const char *name, GLuint (*got)[OU_BRIEF_SIZE], GLuint expected[TILES][OU_BRIEF_SIZE])
{
    bool ok = true;
    for (int t = 0; t < TILES; ++t) {
        char what[64];
        snprintf(what, sizeof(what), "%s tile %d", name, t);
        ok &= ou_check_record(what, got[t], expected[t], 0);
    }
    return ok;
}

/* Tile t's list holds exactly the pixels of [x0, x1) x [y0, y1). */
static bool
check_list(int t, int x0, int x1, int y0, int y1)
{
    const GLuint n = verbose[t][OU_NOHC];
    const GLuint want = (GLuint)((x1 - x0) * (y1 - y0));
    if (n != want) {
        printf("P3 tile %d: list of %u pairs, expected %u\n", t, n, want);
        return false;
    }
    GLuint *pairs = verbose[t] + OU_BRIEF_SIZE;
    ou_sort_pairs(pairs, n);
    for (int y = y0, i = 0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, ++i)
            if (pairs[2 * i] != (GLuint)x || pairs[2 * i + 1] != (GLuint)y) {
                printf("P3 tile %d: pair %d is (%u, %u), expected (%d, %d)\n", t, i, pairs[2 * i],
                       pairs[2 * i + 1], x, y);
                return false;
            }
    return true;
}

static void
passes_in_order(void)
{
    GLuint pass[3];
    a.GenOcclusionPasses(3, pass);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    ou_rect(0, 0, 128, S, 0.25f);                              /* A */
    GLuint *b1[TILES] = {brief[0][0], brief[0][1], brief[0][2]};
    begin_pass(pass[0], GL_BRIEF_OCCLUSION_MESAX, b1, OU_BRIEF_SIZE);
    box();
    a.EndOcclusionPass();
    ou_rect(128, 32, 160, 96, 0.375f);                         /* B */
    GLuint *b2[TILES] = {brief[1][0], brief[1][1], brief[1][2]};
    begin_pass(pass[1], GL_BRIEF_OCCLUSION_MESAX, b2, OU_BRIEF_SIZE);
    box();
    a.EndOcclusionPass();
    glDepthFunc(GL_GREATER);                                   /* C */
    ou_rect(0, 0, S, S, 0.75f);
    glDepthFunc(GL_LESS);
    GLuint *b3[TILES] = {verbose[0], verbose[1], verbose[2]};
    begin_pass(pass[2], GL_VERBOSE_OCCLUSION_MESAX, b3, LIST_WORDS);
    box();
    a.EndOcclusionPass();
    ScissorsMESAX(0, NULL);

    GLint overflowed[3] = {-1, -1, -1};
    for (int p = 0; p < 3; ++p)
        a.GetOcclusionPassiv(pass[p], GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed[p]);
    const bool no_error = piglit_check_gl_error(GL_NO_ERROR);

    GLuint e[TILES][OU_BRIEF_SIZE];
    expect(e[0], 60 * 30, 0, 0, 0, 0, 0);
    expect(e[1], 1, 1, 130, 130, 100, 100);
    expect(e[2], 128 * 128, 32 * 128, 128, 159, 32, 159);
    subtest(no_error && overflowed[0] == 0 && check_pass("P1", brief[0], e), "first-pass-sees-depth-before-it");

    expect(e[2], 128 * 128, 32 * 64, 128, 159, 96, 159);
    subtest(overflowed[1] == 0 && check_pass("P2", brief[1], e), "second-pass-sees-occluder-between");

    expect(e[0], 60 * 30, 60 * 30, 40, 99, 50, 79);
    expect(e[2], 128 * 128, 128 * 128, 32, 159, 32, 159);
    bool ok = overflowed[2] == 0;
    for (int t = 0; t < TILES; ++t) {
        char what[32];
        snprintf(what, sizeof(what), "P3 tile %d", t);
        ok &= ou_check_record(what, verbose[t], e[t], 0);
    }
    ok = ok && check_list(0, 40, 100, 50, 80) && check_list(1, 130, 131, 100, 101) &&
         check_list(2, 32, 160, 32, 160);
    subtest(ok, "verbose-pass-after-render-draw");
    a.DeleteOcclusionPasses(3, pass);
    glDisable(GL_DEPTH_TEST);
}

/* Without a depth buffer an opaque draw over a whole bin makes the bin's
 * earlier work invisible, and an implementation may drop it (llvmpipe
 * does, for bins of draws): not a pass's, which is counted. */
static void
opaque_draw_after_pass(void)
{
    const struct ou_fbo_functions f = ou_fbo_functions();
    GLuint renderbuffers[2];
    ou_make_fbo(&f, S, S, 0, false, renderbuffers);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glClear(GL_COLOR_BUFFER_BIT);

    GLuint pass;
    a.GenOcclusionPasses(1, &pass);
    GLuint *b[TILES] = {brief[0][0], brief[0][1], brief[0][2]};
    begin_pass(pass, GL_BRIEF_OCCLUSION_MESAX, b, OU_BRIEF_SIZE);
    box();
    a.EndOcclusionPass();
    ScissorsMESAX(0, NULL);
    glColor4f(0, 1, 0, 1);
    ou_rect(0, 0, S, S, 0.5f);
    glColor4f(1, 1, 1, 1);
    GLint overflowed = -1;
    a.GetOcclusionPassiv(pass, GL_OCCLUSION_PASS_RESULT_MESAX, &overflowed);
    const bool no_error = piglit_check_gl_error(GL_NO_ERROR);

    GLuint e[TILES][OU_BRIEF_SIZE];
    expect(e[0], 60 * 30, 60 * 30, 40, 99, 50, 79);
    expect(e[1], 1, 1, 130, 130, 100, 100);
    expect(e[2], 128 * 128, 128 * 128, 32, 159, 32, 159);
    subtest(no_error && overflowed == 0 && check_pass("colour-only", brief[0], e),
            "no-depth-buffer-then-opaque-draw");
    a.DeleteOcclusionPasses(1, &pass);
    f.BindFramebuffer(GL_FRAMEBUFFER, piglit_winsys_fbo);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = S;
    config.window_height = S;
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
    a = ou_init_async();
    passes_in_order();
    opaque_draw_after_pass();
    piglit_report_result(result);
}
