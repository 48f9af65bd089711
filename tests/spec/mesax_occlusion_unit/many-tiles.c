/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit with 1 to 64 tiles (the spec's minimum of
 * MAX_OCCLUSION_TILES_MESAX; many-tiles-4096.c goes to occu's drivers'
 * 4096): one column-wide tile per column, overlapping tiles, tiles larger than
 * the framebuffer (8192 x 8192) or reaching past INT_MAX, and empty tiles.
 * A fragment counts in every tile it lies in.
 *
 * Tolerances: counts, coordinates and depth exact. The band lies at
 * z = 0.5, which float32 and the transforms of ou_init carry without
 * rounding (counts-analytic.c gives the arithmetic), so its record depth is
 * ou_depth(0.5); the 24-bit depth buffer's value of it is about 128 units
 * away and must not pass.
 */
#include <limits.h>
#include <stdlib.h>

#include "ou_util.h"

#define W 80
#define H 40
#define ZTOL 0

static void draw_band(void) { ou_rect(0, 10, W, 30, 0.5f); }   /* rows 10..29, all columns */

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
    GLint max_tiles = 0;
    glGetIntegerv(GL_MAX_OCCLUSION_TILES_MESAX, &max_tiles);
    if (max_tiles > 64)
        max_tiles = 64;
    GLuint (*rec)[OU_BRIEF_SIZE] = calloc(64, sizeof(*rec));
    GLint tiles[64 * 4];

    /* 1, 4, 16 and MAX tiles: tile i is column i. */
    const int counts[4] = {1, 4, 16, max_tiles};
    for (int c = 0; c < 4; ++c) {
        const int n = counts[c];
        for (int i = 0; i < n; ++i) {
            tiles[4 * i] = i;
            tiles[4 * i + 1] = 0;
            tiles[4 * i + 2] = 1;
            tiles[4 * i + 3] = H;
        }
        ou_brief_pass(n, tiles, rec, draw_band);
        bool ok = piglit_check_gl_error(GL_NO_ERROR);
        for (int i = 0; i < n && ok; ++i) {
            const GLuint expected[OU_BRIEF_SIZE] = {20, 20, (GLuint)i, (GLuint)i, 10, 29, ou_depth(0.5), ou_depth(0.5)};
            char what[64];
            snprintf(what, sizeof(what), "%d tiles, tile %d", n, i);
            ok = ou_check_record(what, rec[i], expected, ZTOL);
        }
        piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "column-tiles-%d", n);
        if (!ok)
            result = PIGLIT_FAIL;
    }

    /* Overlapping, huge, empty and past-INT_MAX tiles in one pass. */
    const GLint mixed[6 * 4] = {
        0, 0, 40, H,                 /* left half */
        20, 0, 40, H,                /* overlaps it by 20 columns */
        -4096, -4096, 8192, 8192,    /* larger than the framebuffer, covers it */
        10, 10, 0, 5,                /* empty: width 0 */
        INT_MAX - 5, 0, INT_MAX, H,  /* x + width past INT_MAX, off-screen */
        -10, 15, 15, INT_MAX,        /* columns 0..4, rows 15.. (height past INT_MAX) */
    };
    ou_brief_pass(6, mixed, rec, draw_band);
    const GLuint z = ou_depth(0.5);
    const GLuint e = OU_EMPTY_MIN, o = OU_EMPTY_MAX;
    bool ok = piglit_check_gl_error(GL_NO_ERROR) &&
              ou_check_record("left half", rec[0], (GLuint[]){800, 800, 0, 39, 10, 29, z, z}, ZTOL) &&
              ou_check_record("overlapping", rec[1], (GLuint[]){800, 800, 20, 59, 10, 29, z, z}, ZTOL) &&
              ou_check_record("8192x8192", rec[2], (GLuint[]){1600, 1600, 0, W - 1, 10, 29, z, z}, ZTOL) &&
              ou_check_record("empty", rec[3], (GLuint[]){0, 0, e, o, e, o, e, o}, 0) &&
              ou_check_record("past INT_MAX x", rec[4], (GLuint[]){0, 0, e, o, e, o, e, o}, 0) &&
              ou_check_record("past INT_MAX height", rec[5], (GLuint[]){75, 75, 0, 4, 15, 29, z, z}, ZTOL);
    piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "overlapping-huge-empty-tiles");
    if (!ok)
        result = PIGLIT_FAIL;

    free(rec);
    piglit_report_result(result);
}
