/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: an overflowed verbose list keeps the first pairs
 * in raster order (window y ascending, then x) of all the tile's
 * non-occluded fragments, in that order (section 5.X), so that the same
 * scene gives the same record on every driver and for every number of
 * rasterizer threads (meson runs this test under llvmpipe with
 * LP_NUM_THREADS 0, 1, 2 and 8 too).
 *
 * The true list comes from a pass with room for every pair; the
 * overflowed ones must be its sorted prefix, word for word.
 *
 * Subtests:
 *   window-quad-keeps-first-rows    a 512 x 512 quad, room for 500 pairs:
 *                                   the first 500 of row 0
 *   overlapping-triangles-prefix    two overlapping triangles, partly
 *                                   depth-occluded by a third, duplicate
 *                                   positions included: room for 700
 *   same-record-30-times            30 identical overflowing passes give
 *                                   the same 500 pairs
 *   fbo-rows-keep-gl-order          the same in a framebuffer object
 *                                   (rows not flipped), room for 300
 */
#include "ou_util.h"

#define S 512

static GLuint *big, *small;

static void
scene_triangles(void)
{
    glBegin(GL_TRIANGLES);
    glVertex3f(13.5f, 20.25f, 0.6f);
    glVertex3f(400.0f, 90.0f, 0.6f);
    glVertex3f(120.0f, 470.0f, 0.6f);
    glVertex3f(60.0f, 400.0f, 0.55f);
    glVertex3f(500.0f, 300.0f, 0.55f);
    glVertex3f(30.0f, 10.0f, 0.55f);
    glEnd();
}

/* One verbose pass over `draw` with room for `pairs` pairs; returns NOHC. */
static GLuint
pass(void (*draw)(void), GLuint *buffer, GLsizei pairs)
{
    GLuint *buffers[1] = {buffer};
    GLsizei sizes[1] = {8 + 2 * pairs + 1};   /* odd: `pairs` before the terminator */
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw();
    glRenderMode(GL_RENDER);
    return buffer[OU_NOHC];
}

static void
window_quad(void)
{
    ou_rect(0, 0, S, S, 0.5f);
}

static void
occluded_triangles(void)
{
    scene_triangles();
}

/* The overflowed list of `draw` (room `room`) equals the first `room`
 * pairs, sorted, of its full list. */
static bool
prefix_of_true_list(const char *name, void (*draw)(void), GLsizei room)
{
    const GLuint n = pass(draw, big, 2 * S * S);
    if (n <= (GLuint)room || n > (GLuint)(2 * S * S)) {
        printf("%s: %u fragments, the test needs more than %d and at most %d\n", name, n, room, 2 * S * S);
        subtest(false, name);
        return false;
    }
    ou_sort_pairs(big + 8, n);
    pass(draw, small, room);
    bool ok = small[OU_NOHC] == n && small[8 + 2 * room] == 0xffffffffu;
    for (GLsizei i = 0; ok && i < 2 * room; ++i)
        ok = small[8 + i] == big[8 + i];
    if (!ok)
        printf("%s: NOHC %u (%u), first pair (%u, %u), expected (%u, %u)\n", name, small[OU_NOHC], n, small[8],
               small[9], big[8], big[9]);
    subtest(ok, name);
    return ok;
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
    ou_init();
    big = malloc(sizeof(GLuint) * (8 + 4 * S * S + 1));
    small = malloc(sizeof(GLuint) * (8 + 2 * 1000 + 1));
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClear(GL_DEPTH_BUFFER_BIT);

    prefix_of_true_list("window-quad-keeps-first-rows", window_quad, 500);

    /* An occluder in front of part of the triangles. */
    ou_rect(200, 150, 320, 260, 0.3f);
    prefix_of_true_list("overlapping-triangles-prefix", occluded_triangles, 700);

    glClear(GL_DEPTH_BUFFER_BIT);
    static GLuint first[8 + 1001];
    pass(window_quad, first, 500);
    bool same = true;
    for (int k = 0; k < 30 && same; ++k) {
        pass(window_quad, small, 500);
        same = memcmp(small, first, sizeof(first)) == 0;
    }
    subtest(same, "same-record-30-times");

    const struct ou_fbo_functions f = ou_fbo_functions();
    GLuint rb[2];
    ou_make_fbo(&f, S, S, 0, true, rb);
    glClear(GL_DEPTH_BUFFER_BIT);
    prefix_of_true_list("fbo-rows-keep-gl-order", occluded_triangles, 300);

    free(big);
    free(small);
    piglit_report_result(result);
}
