/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: a point sprite across an edge of the framebuffer
 * counts the same whatever the tile layout or the mode, and a record with
 * NOHC > 0 has its box inside the framebuffer (spec section 5.X): the
 * fragments outside it are never produced (OpenGL 4.6, section 14.4).
 *
 * A 203 x 150 window-system framebuffer (neither side a multiple of
 * llvmpipe's 64-pixel bins, whose last row and column of bins then reach
 * past it); depth test off. Sprites of sizes 4, 8 and 33 centred half a
 * pixel inside an edge. For each, these must all equal the pixels it
 * writes in RENDER mode (counted from glReadPixels, tolerance 0):
 *   - NOHC of a brief pass with the default tile;
 *   - the sum of NOHC over a brief pass with two tiles that split the
 *     window at the sprite's centre, across the edge's direction;
 *   - NOHC of a verbose pass (the size of its list);
 *   - GL_SAMPLES_PASSED of the RENDER-mode draw;
 * and the default tile's box must be the box of the written pixels.
 *
 * Subtests: bottom-edge, top-edge, left-edge, right-edge.
 */
#include "ou_util.h"

enum { W = 203, H = 150 };

static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;

static float sprite_x, sprite_y;

static void
draw_sprite(void)
{
    glBegin(GL_POINTS);
    glVertex3f(sprite_x, sprite_y, 0.5f);
    glEnd();
}

static bool
sprite_counts_agree(const char *edge, float size, float x, float y, bool vertical_edge)
{
    static GLuint list[8 + 2 * W * H];
    GLuint query, samples = 0xdeadbeefu;
    char what[96];

    snprintf(what, sizeof(what), "%s, size %g", edge, size);
    sprite_x = x;
    sprite_y = y;
    glPointSize(size);

    glClear(GL_COLOR_BUFFER_BIT);
    GenQueries(1, &query);
    BeginQuery(GL_SAMPLES_PASSED, query);
    draw_sprite();
    EndQuery(GL_SAMPLES_PASSED);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    GLuint expected[OU_BRIEF_SIZE];
    ou_record_of_drawn_pixels(W, H, 0.5, expected);
    const GLuint n = expected[OU_NOHC];

    GLuint record[2][OU_BRIEF_SIZE];
    bool ok = ou_brief_pass(0, NULL, record, draw_sprite) == 0;
    ok = ou_check_record(what, record[0], expected, OU_Z24_READBACK_TOLERANCE) && ok;

    /* Two tiles meeting at the sprite's centre, along the edge. */
    const GLint cx = (GLint)x, cy = (GLint)y;
    const GLint split[2][4] = {
        {0, 0, vertical_edge ? W : cx, vertical_edge ? cy : H},
        {vertical_edge ? 0 : cx, vertical_edge ? cy : 0, vertical_edge ? W : W - cx, vertical_edge ? H - cy : H},
    };
    ok = ou_brief_pass(2, &split[0][0], record, draw_sprite) == 0 && ok;
    const GLuint split_nohc = record[0][OU_NOHC] + record[1][OU_NOHC];

    GLsizei size_words = (GLsizei)(sizeof(list) / sizeof(list[0]));
    GLuint *buffers[1] = {list};
    ou_fill(list, size_words);
    OcclusionBuffersMESAX(1, &size_words, buffers);
    glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    draw_sprite();
    ok = glRenderMode(GL_RENDER) == 0 && ok;

    if (samples != n || split_nohc != n || list[OU_NOHC] != n || n == 0) {
        printf("%s: %u pixels written, GL_SAMPLES_PASSED %u, NOHC of two tiles %u, verbose NOHC %u\n", what, n,
               samples, split_nohc, list[OU_NOHC]);
        ok = false;
    }
    return ok;
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
        bool vertical;
    } edges[] = {
        {"bottom-edge", 100.5f, 0.5f, false},
        {"top-edge", 100.5f, H - 0.5f, false},
        {"left-edge", 0.5f, 75.5f, true},
        {"right-edge", W - 0.5f, 75.5f, true},
    };

    ou_init();
    GenQueries = glGenQueries;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    GetQueryObjectuiv = glGetQueryObjectuiv;
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_POINT_SPRITE);
    glClearColor(0, 0, 0, 0);
    glColor4f(1, 1, 1, 1);

    for (unsigned e = 0; e < sizeof(edges) / sizeof(edges[0]); ++e) {
        bool ok = true;
        for (unsigned s = 0; s < sizeof(sizes) / sizeof(sizes[0]); ++s)
            ok = sprite_counts_agree(edges[e].name, sizes[s], edges[e].x, edges[e].y, edges[e].vertical) && ok;
        subtest(ok && piglit_check_gl_error(GL_NO_ERROR), edges[e].name);
    }
    piglit_report_result(result);
}
