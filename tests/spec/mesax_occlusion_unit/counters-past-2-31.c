/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: counters past 2^31 and 2^32 (spec issue 5).
 * A 2048 x 2048 window (2^22 pixels) covered by 1040 full-window
 * rectangles, depth test off, in one brief pass with two tiles:
 *   half    the left half: 1040 * 2^21 = 2 181 038 080 fragments, past 2^31,
 *           exact in the 32-bit record;
 *   whole   the window: 1040 * 2^22 = 4 362 076 160, past 2^32, recorded
 *           as 2^32 - 1 (saturated, not wrapped to 67 108 864).
 * Exact. Runs on llvmpipe only: softpipe needs minutes for 4.4 billion
 * fragments, and the saturation is the state tracker's, shared by both.
 */
#include <string.h>

#include "ou_util.h"

#define SIZE 2048

static int layers;
static void
draw_layers(void)
{
    for (int i = 0; i < layers; ++i)
        ou_rect(0, 0, SIZE, SIZE, 0.5f);
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = SIZE;
    config.window_height = SIZE;
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
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    if (!strstr(renderer, "llvmpipe")) {
        printf("runs on llvmpipe only (softpipe would take minutes)\n");
        piglit_report_result(PIGLIT_SKIP);
    }
    glDisable(GL_DEPTH_TEST);
    GLuint rec[2][OU_BRIEF_SIZE];
    const GLint tiles[8] = {0, 0, SIZE / 2, SIZE, 0, 0, SIZE, SIZE};
    layers = 1040;
    ou_brief_pass(2, tiles, rec, draw_layers);

    const GLuint half = 1040u * (SIZE / 2) * SIZE;   /* 2 181 038 080 */
    if (rec[0][OU_NOHC] != half)
        printf("half: NOHC %u, expected %u\n", rec[0][OU_NOHC], half);
    subtest(rec[0][OU_NOHC] == half && rec[0][OU_PHC] == half && rec[0][OU_XMAX] == SIZE / 2 - 1,
            "past-2^31-exact");
    if (rec[1][OU_NOHC] != 0xffffffffu)
        printf("whole: NOHC %u, expected 4294967295 (saturated)\n", rec[1][OU_NOHC]);
    subtest(rec[1][OU_NOHC] == 0xffffffffu && rec[1][OU_PHC] == 0xffffffffu && rec[1][OU_XMAX] == SIZE - 1,
            "past-2^32-saturates");

    piglit_report_result(result);
}
