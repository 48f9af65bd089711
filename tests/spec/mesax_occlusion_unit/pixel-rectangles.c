/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: the fragments of pixel rectangles and bitmaps
 * are counted in an occlusion mode (spec issue 11, the section 4.3.3 edit
 * and section 5.X), as those of polygons are, and write nothing. Each
 * subtest makes a brief pass with one tile over the window, against a depth
 * buffer whose left half holds an occluder at depth 0.25 and whose right
 * half is clear (1.0):
 *   draw-pixels-color    DrawPixels RGBA 16x16 at raster depth 0.5 over
 *                        both halves: PHC 256, NOHC 128 (the right half);
 *   draw-pixels-depth    DrawPixels DEPTH_COMPONENT 16x16 of depth 0.1:
 *                        every fragment nearer than both halves: 256/256;
 *   copy-pixels-color    CopyPixels 16x16 of colour at raster depth 0.5:
 *                        256/128, as DrawPixels;
 *   bitmap               Bitmap 16x16 with 100 bits set at depth 0.5, all
 *                        over the clear half: 100/100;
 *   draw-pixels-stencil  DrawPixels STENCIL_INDEX 16x16: its fragments take
 *                        no part in the depth test in GL_RENDER (the state
 *                        tracker draws them with depth testing off), so
 *                        256/256, as GL_SAMPLES_PASSED counts them in
 *                        GL_RENDER (checked in the same subtest);
 * and every pass leaves colour, depth and stencil as they were.
 */
#include "ou_util.h"

#define W 64
#define H 32

static PFNGLGENQUERIESPROC GenQueries;
static PFNGLBEGINQUERYPROC BeginQuery;
static PFNGLENDQUERYPROC EndQuery;
static PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;

static GLubyte colour_pixels[16 * 16 * 4];
static GLfloat depth_pixels[16 * 16];
static GLubyte stencil_pixels[16 * 16];
static GLubyte bitmap_bits[16 * 2];

/* Left half (x < 32) occluded at depth 0.25; right half clear. */
static void
paint_scene(void)
{
    glClearColor(0.1f, 0.2f, 0.3f, 1.0f);
    glClearDepth(1.0);
    glClearStencil(5);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glColor4f(1, 1, 1, 1);
    ou_rect(0, 0, 32, H, 0.25f);
}

/* Rectangles straddle x = 32: columns 24..39. */
static void draw_pixels_color(void) { glRasterPos3f(24, 8, 0.5f); glDrawPixels(16, 16, GL_RGBA, GL_UNSIGNED_BYTE, colour_pixels); }
static void draw_pixels_depth(void) { glRasterPos3f(24, 8, 0.5f); glDrawPixels(16, 16, GL_DEPTH_COMPONENT, GL_FLOAT, depth_pixels); }
static void copy_pixels_color(void) { glRasterPos3f(24, 8, 0.5f); glCopyPixels(40, 8, 16, 16, GL_COLOR); }
static void bitmap(void) { glRasterPos3f(40, 8, 0.5f); glBitmap(16, 16, 0, 0, 0, 0, bitmap_bits); }
static void draw_pixels_stencil(void) { glRasterPos3f(24, 8, 0.5f); glDrawPixels(16, 16, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil_pixels); }

static GLuint
samples_in_render_mode(void (*draw)(void))
{
    GLuint query, samples = 0;
    GenQueries(1, &query);
    BeginQuery(GL_SAMPLES_PASSED, query);
    draw();
    EndQuery(GL_SAMPLES_PASSED);
    GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
    paint_scene();   /* what the draw wrote is gone again */
    return samples;
}

static void
check(const char *name, void (*draw)(void), GLuint phc, GLuint nohc, bool against_render_mode)
{
    static GLubyte colour0[W * H * 4], colour1[W * H * 4], stencil0[W * H], stencil1[W * H];
    static GLuint depth0[W * H], depth1[W * H];
    paint_scene();
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, colour0);
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, depth0);
    glReadPixels(0, 0, W, H, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil0);
    GLuint record[1][OU_BRIEF_SIZE];
    ou_brief_pass(0, NULL, record, draw);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, colour1);
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, depth1);
    glReadPixels(0, 0, W, H, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil1);
    const bool unchanged = !memcmp(colour0, colour1, sizeof(colour0)) && !memcmp(depth0, depth1, sizeof(depth0)) &&
                           !memcmp(stencil0, stencil1, sizeof(stencil0));
    bool ok = record[0][OU_PHC] == phc && record[0][OU_NOHC] == nohc && unchanged && piglit_check_gl_error(GL_NO_ERROR);
    if (against_render_mode) {
        const GLuint samples = samples_in_render_mode(draw);
        if (samples != nohc) {
            printf("%s: GL_SAMPLES_PASSED in GL_RENDER %u, the pass's NOHC %u\n", name, samples, record[0][OU_NOHC]);
            ok = false;
        }
    }
    if (!ok)
        printf("%s: PHC %u NOHC %u (expected %u %u), framebuffer %s\n", name, record[0][OU_PHC],
               record[0][OU_NOHC], phc, nohc, unchanged ? "unchanged" : "CHANGED");
    subtest(ok, name);
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
    GenQueries = glGenQueries;
    BeginQuery = glBeginQuery;
    EndQuery = glEndQuery;
    GetQueryObjectuiv = glGetQueryObjectuiv;
    if (!GenQueries || !BeginQuery || !EndQuery || !GetQueryObjectuiv) {
        printf("needs occlusion queries (GL 1.5)\n");
        piglit_report_result(PIGLIT_FAIL);
    }
    memset(colour_pixels, 0xc0, sizeof(colour_pixels));
    for (int i = 0; i < 16 * 16; ++i) {
        depth_pixels[i] = 0.1f;
        stencil_pixels[i] = 9;
    }
    /* 100 bits: rows 0..9 with their first 10 bits set (rows are 2 bytes). */
    for (int row = 0; row < 10; ++row) {
        bitmap_bits[row * 2] = 0xff;
        bitmap_bits[row * 2 + 1] = 0xc0;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);

    check("draw-pixels-color", draw_pixels_color, 256, 128, true);
    check("draw-pixels-depth", draw_pixels_depth, 256, 256, true);
    check("copy-pixels-color", copy_pixels_color, 256, 128, true);
    check("bitmap", bitmap, 100, 100, true);
    check("draw-pixels-stencil", draw_pixels_stencil, 256, 256, true);
    /* Mesa 22.3.6, unpatched as well, crashes destroying a context that
     * drew pixel rectangles while immediate-mode vertices are pending
     * (glDrawPixels, glBegin/glEnd, OSMesaDestroyContext: a use after free
     * in the vertex flush, seen under MALLOC_PERTURB_). Not this
     * extension's; the test flushes before it ends.
     */
    glFinish();
    piglit_report_result(result);
}
