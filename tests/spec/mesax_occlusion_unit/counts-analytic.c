/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: exact NOHC, PHC, bounding box and depth range
 * for coverage known analytically: axis-aligned rectangles on pixel
 * boundaries (no rasterization ambiguity), a half-occluded rectangle, a
 * fully occluded one, tiles that cut a rectangle's edges, and the default
 * tile, which is taken when the pass begins (a Scissor or Viewport call
 * during the pass changes the scissor test and the rasterization, not the
 * tile).
 *
 * Tolerances: counts, coordinates and depth exact. The rectangles lie at
 * z = 0.5, which float32 holds exactly and which glOrtho(..., 0, -1) and
 * the viewport transform map to itself without rounding (2 * 0.5 - 1 = 0,
 * then 0 * 0.5 + 0.5), so the record is ou_depth(0.5) = 0x80000000. A
 * record of the 24-bit depth buffer's value instead would be half a buffer
 * step off (0.5 * (2^24 - 1) lies half-way between two steps), about 128
 * units: any tolerance would have to stay below that, and none is needed.
 */
#include "ou_util.h"

#define W 64
#define H 64
#define ZTOL 0


static void
check(const char *name, const GLuint *got, const GLuint expected[OU_BRIEF_SIZE])
{
    bool ok = ou_check_record(name, got, expected, ZTOL) && piglit_check_gl_error(GL_NO_ERROR);
    piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "%s", name);
    if (!ok)
        result = PIGLIT_FAIL;
}

/* The tested object: 20 x 10 pixels at depth 0.5. */
static void draw_target(void) { ou_rect(10, 20, 30, 30, 0.5f); }

/* Viewport and projection 0..width-1 wide, pixel-exact as ou_init sets them. */
static void
set_viewport(int width)
{
    glViewport(0, 0, width, H);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, width, 0, H, 0, -1);
    glMatrixMode(GL_MODELVIEW);
}

static void
widen_viewport_and_draw_target(void)
{
    set_viewport(W);
    draw_target();
}

static void
widen_scissor_and_draw_target(void)
{
    glScissor(0, 0, W, H);
    draw_target();
}

static void
disable_indexed_scissor_and_draw_target(void)
{
    PFNGLSCISSORINDEXEDPROC ScissorIndexed = glScissorIndexed;
    PFNGLDISABLEIPROC Disablei = glDisablei;
    ScissorIndexed(0, 0, 0, W, H);
    Disablei(GL_SCISSOR_TEST, 0);
    draw_target();
}

static void
reset_depth(void)
{
    glDepthMask(GL_TRUE);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
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
    ou_init();
    GLuint rec[4][OU_BRIEF_SIZE];
    const GLuint z = ou_depth(0.5);

    /* Depth test off: every fragment is non-occluded. */
    glDisable(GL_DEPTH_TEST);
    ou_brief_pass(0, NULL, rec, draw_target);
    check("no-depth-test", rec[0], (GLuint[]){200, 200, 10, 29, 20, 29, z, z});

    /* Depth test on, empty depth buffer. */
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    reset_depth();
    ou_brief_pass(0, NULL, rec, draw_target);
    check("unoccluded", rec[0], (GLuint[]){200, 200, 10, 29, 20, 29, z, z});

    /* The left half hidden by a nearer occluder drawn in GL_RENDER. */
    reset_depth();
    ou_rect(10, 20, 20, 30, 0.25f);
    ou_brief_pass(0, NULL, rec, draw_target);
    check("half-occluded", rec[0], (GLuint[]){100, 200, 20, 29, 20, 29, z, z});

    /* Tiles cutting the half-occluded rectangle's edges; one off-screen, one 1x1. */
    const GLint tiles[16] = {
        25, 0, 100, 100,   /* columns 25..29 of the visible half: 5 x 10 */
        0, 25, 15, 5,      /* rows 25..29, columns 10..14: all occluded */
        -50, -50, 10, 10,  /* off-screen */
        29, 29, 1, 1,      /* the top-right pixel */
    };
    ou_brief_pass(4, tiles, rec, draw_target);
    check("tile-cuts-right-edge", rec[0], (GLuint[]){50, 50, 25, 29, 20, 29, z, z});
    check("tile-cuts-left-edge-occluded", rec[1],
          (GLuint[]){0, 25, OU_EMPTY_MIN, OU_EMPTY_MAX, OU_EMPTY_MIN, OU_EMPTY_MAX, OU_EMPTY_MIN, OU_EMPTY_MAX});
    check("tile-off-screen", rec[2],
          (GLuint[]){0, 0, OU_EMPTY_MIN, OU_EMPTY_MAX, OU_EMPTY_MIN, OU_EMPTY_MAX, OU_EMPTY_MIN, OU_EMPTY_MAX});
    check("tile-1x1", rec[3], (GLuint[]){1, 1, 29, 29, 29, 29, z, z});

    /* Fully occluded: NOHC 0, PHC the projection, empty extents. */
    reset_depth();
    ou_rect(0, 0, W, H, 0.1f);
    ou_brief_pass(0, NULL, rec, draw_target);
    check("fully-occluded", rec[0],
          (GLuint[]){0, 200, OU_EMPTY_MIN, OU_EMPTY_MAX, OU_EMPTY_MIN, OU_EMPTY_MAX, OU_EMPTY_MIN, OU_EMPTY_MAX});

    /* glScissor as the default tile (scissor test on): the tile and the
     * scissor test both cut the rectangle to columns 10..14. */
    reset_depth();
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 15, H);
    ou_brief_pass(0, NULL, rec, draw_target);
    glDisable(GL_SCISSOR_TEST);
    check("scissor-is-default-tile", rec[0], (GLuint[]){50, 50, 10, 14, 20, 29, z, z});

    /* The viewport is the default tile without the scissor test. */
    set_viewport(20);
    ou_brief_pass(0, NULL, rec, draw_target);
    check("viewport-is-default-tile", rec[0], (GLuint[]){100, 100, 10, 19, 20, 29, z, z});

    /* Viewport 0..19 is the tile; widened during the pass, it lets the
     * whole rectangle through, and the tile still stops at column 19. */
    ou_brief_pass(0, NULL, rec, widen_viewport_and_draw_target);
    check("viewport-change-during-pass-keeps-tile", rec[0], (GLuint[]){100, 100, 10, 19, 20, 29, z, z});
    set_viewport(W);

    /* Scissor box 0..14 is the tile; widened during the pass, it lets the
     * whole rectangle through, and the tile still stops at column 14. */
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 15, H);
    ou_brief_pass(0, NULL, rec, widen_scissor_and_draw_target);
    glDisable(GL_SCISSOR_TEST);
    check("scissor-change-during-pass-keeps-tile", rec[0], (GLuint[]){50, 50, 10, 14, 20, 29, z, z});

    /* The same through ARB_viewport_array's indexed scissor commands:
     * disabling the test for index 0 during the pass keeps the tile. */
    if (piglit_is_extension_supported("GL_ARB_viewport_array")) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, 0, 15, H);
        ou_brief_pass(0, NULL, rec, disable_indexed_scissor_and_draw_target);
        glDisable(GL_SCISSOR_TEST);
        check("indexed-scissor-change-during-pass-keeps-tile", rec[0], (GLuint[]){50, 50, 10, 14, 20, 29, z, z});
    } else {
        ou_subtest_unsupported("indexed-scissor-change-during-pass-keeps-tile", "GL_ARB_viewport_array");
    }

    piglit_report_result(result);
}
