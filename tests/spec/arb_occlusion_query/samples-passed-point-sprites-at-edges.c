/* SPDX-License-Identifier: MIT */
/*
 * GL_SAMPLES_PASSED counts the fragments a point sprite produces inside the
 * framebuffer, no more, when the sprite lies across one of its edges: the
 * pixels it writes (OpenGL 4.6, section 4.2.1: the count is of samples that
 * pass the per-fragment tests; a fragment outside the framebuffer is never
 * produced, section 14.4).
 *
 * A 203 x 150 window-system framebuffer (neither side a multiple of
 * llvmpipe's 64-pixel bins, so that the bins along the top and right edges
 * reach past it); the depth test off. Each sprite is drawn white on black
 * inside a GL_SAMPLES_PASSED query and the white pixels are counted from
 * glReadPixels; the two numbers must be equal (tolerance 0: both count
 * whole pixels of a single-sampled buffer). Sprite sizes 4, 8 and 33 with
 * their centres on a pixel's centre half a pixel inside the edge, so that
 * each sprite reaches 1.5, 3.5 and 16 pixels past it.
 *
 * Subtests: bottom-edge, top-edge, left-edge, right-edge.
 */
#include <stdio.h>
#include <string.h>

#include "piglit-util-gl.h"

enum { W = 203, H = 150 };

static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;

static bool
sprite_counts_agree(const char *edge, float size, float x, float y)
{
    static GLubyte pixels[H][W][4];
    GLuint query, samples = 0xdeadbeefu, written = 0;

    glClear(GL_COLOR_BUFFER_BIT);
    glPointSize(size);
    GenQueries(1, &query);
    BeginQuery(GL_SAMPLES_PASSED, query);
    glBegin(GL_POINTS);
    glVertex2f(x, y);
    glEnd();
    EndQuery(GL_SAMPLES_PASSED);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    for (int row = 0; row < H; ++row)
        for (int col = 0; col < W; ++col)
            written += pixels[row][col][0] != 0;
    if (samples != written || written == 0)
        printf("%s, size %g at (%g, %g): GL_SAMPLES_PASSED %u, %u pixels written\n", edge, size, x, y, samples,
               written);
    return samples == written && written > 0;
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
    static const float sizes[] = {4.0f, 8.0f, 33.0f};
    static const struct {
        const char *name;
        float x, y;
    } edges[] = {
        {"bottom-edge", 100.5f, 0.5f},
        {"top-edge", 100.5f, H - 0.5f},
        {"left-edge", 0.5f, 75.5f},
        {"right-edge", W - 0.5f, 75.5f},
    };
    enum piglit_result result = PIGLIT_PASS;

    GenQueries = glGenQueries;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    GetQueryObjectuiv = glGetQueryObjectuiv;
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, W, 0, H, -1, 1);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_POINT_SPRITE);
    glClearColor(0, 0, 0, 0);
    glColor4f(1, 1, 1, 1);

    for (unsigned e = 0; e < sizeof(edges) / sizeof(edges[0]); ++e) {
        bool ok = true;
        for (unsigned s = 0; s < sizeof(sizes) / sizeof(sizes[0]); ++s)
            ok = sprite_counts_agree(edges[e].name, sizes[s], edges[e].x, edges[e].y) && ok;
        ok = piglit_check_gl_error(GL_NO_ERROR) && ok;
        piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "%s", edges[e].name);
        if (!ok)
            result = PIGLIT_FAIL;
    }
    piglit_report_result(result);
}
