/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit, numerically hard cases. Where the spec defines
 * the result by what GL_RENDER would do, the test compares with a
 * GL_RENDER draw of the same geometry (the pixels whose depth changes):
 *   box-straddles-near-plane, eye-inside-box (perspective, back faces culled)
 * and elsewhere with exact expectations:
 *   depth-0-and-1, huge-coordinates, zero-area, sub-pixel.
 */
#include <stdlib.h>

#include "ou_util.h"

#define W 64
#define H 64

static GLuint rec[1][OU_BRIEF_SIZE];


/* An axis-aligned box, faces wound counter-clockwise seen from outside. */
static float box_lo[3], box_hi[3];
static void
draw_box(void)
{
    const float *l = box_lo, *h = box_hi;
    glBegin(GL_QUADS);
    glVertex3f(l[0], l[1], h[2]); glVertex3f(h[0], l[1], h[2]); glVertex3f(h[0], h[1], h[2]); glVertex3f(l[0], h[1], h[2]);
    glVertex3f(h[0], l[1], l[2]); glVertex3f(l[0], l[1], l[2]); glVertex3f(l[0], h[1], l[2]); glVertex3f(h[0], h[1], l[2]);
    glVertex3f(l[0], l[1], l[2]); glVertex3f(l[0], l[1], h[2]); glVertex3f(l[0], h[1], h[2]); glVertex3f(l[0], h[1], l[2]);
    glVertex3f(h[0], l[1], h[2]); glVertex3f(h[0], l[1], l[2]); glVertex3f(h[0], h[1], l[2]); glVertex3f(h[0], h[1], h[2]);
    glVertex3f(l[0], h[1], h[2]); glVertex3f(h[0], h[1], h[2]); glVertex3f(h[0], h[1], l[2]); glVertex3f(l[0], h[1], l[2]);
    glVertex3f(l[0], l[1], l[2]); glVertex3f(h[0], l[1], l[2]); glVertex3f(h[0], l[1], h[2]); glVertex3f(l[0], l[1], h[2]);
    glEnd();
}

/* Pixels whose depth a GL_RENDER draw changes, from a cleared depth buffer. */
static GLuint
render_changed_pixels(void (*draw)(void))
{
    static GLuint before[W * H], after[W * H];
    glClear(GL_DEPTH_BUFFER_BIT);
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, before);
    draw();
    glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, after);
    GLuint n = 0;
    for (int i = 0; i < W * H; ++i)
        n += before[i] != after[i];
    glClear(GL_DEPTH_BUFFER_BIT);
    return n;
}

static void
perspective(void)
{
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-0.1, 0.1, -0.1, 0.1, 0.1, 100.0);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
}

static void
window_ortho(void)
{
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, W, 0, H, 0, -1);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
}

static void tri_zero_area(void) { glBegin(GL_TRIANGLES); glVertex3f(5, 5, .5f); glVertex3f(20, 20, .5f); glVertex3f(35, 35, .5f); glEnd(); }
static void tri_misses_centres(void) { glBegin(GL_TRIANGLES); glVertex3f(10.6f, 10.6f, .5f); glVertex3f(10.9f, 10.6f, .5f); glVertex3f(10.6f, 10.9f, .5f); glEnd(); }
static void tri_one_centre(void) { glBegin(GL_TRIANGLES); glVertex3f(10.2f, 10.2f, .5f); glVertex3f(11.0f, 10.2f, .5f); glVertex3f(10.2f, 11.0f, .5f); glEnd(); }
static void rect_z0(void) { ou_rect(0, 0, 8, 8, 0.0f); }
static void rect_z1(void) { ou_rect(0, 0, 8, 8, 1.0f); }
static float huge_scale;
static void huge(void)
{
    glBegin(GL_TRIANGLES);
    glVertex3f(-huge_scale, -huge_scale, 0.5f);
    glVertex3f(huge_scale, -huge_scale, 0.5f);
    glVertex3f(0.0f, huge_scale, 0.5f);
    glEnd();
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
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);

    /* A box from 0.05 to 2 in front of the eye, to its right: its face
     * x = 0.05 faces the eye and the near plane (0.1) cuts it. */
    perspective();
    box_lo[0] = 0.05f; box_lo[1] = -0.5f; box_lo[2] = -2.0f;
    box_hi[0] = 1.0f; box_hi[1] = 0.5f; box_hi[2] = -0.05f;
    GLuint expected = render_changed_pixels(draw_box);
    ou_brief_pass(0, NULL, rec, draw_box);
    if (rec[0][OU_NOHC] != expected)
        printf("near plane: NOHC %u, GL_RENDER changes %u pixels\n", rec[0][OU_NOHC], expected);
    subtest(expected > 100 && rec[0][OU_NOHC] == expected && rec[0][OU_PHC] == expected, "box-straddles-near-plane");

    /* The eye inside the box: every face is a back face and is culled, so
     * the box produces no fragment at all (spec issue 13). */
    box_lo[0] = -1; box_lo[1] = -1; box_lo[2] = -1;
    box_hi[0] = 1; box_hi[1] = 1; box_hi[2] = 1;
    expected = render_changed_pixels(draw_box);
    ou_brief_pass(0, NULL, rec, draw_box);
    subtest(expected == 0 && rec[0][OU_NOHC] == 0 && rec[0][OU_PHC] == 0, "eye-inside-box");
    glDisable(GL_CULL_FACE);

    /* Depth 0 and 1 map to 0 and 0xFFFFFFFF exactly. */
    window_ortho();
    glDepthFunc(GL_LEQUAL);
    ou_brief_pass(0, NULL, rec, rect_z0);
    bool ok = ou_check_record("z = 0", rec[0], (GLuint[]){64, 64, 0, 7, 0, 7, 0, 0}, 0);
    ou_brief_pass(0, NULL, rec, rect_z1);
    ok = ou_check_record("z = 1", rec[0], (GLuint[]){64, 64, 0, 7, 0, 7, 0xffffffffu, 0xffffffffu}, 0) && ok;
    subtest(ok, "depth-0-and-1");
    glDepthFunc(GL_LESS);

    /* A triangle with vertices at +-1e6 covers the whole window. */
    huge_scale = 1e6f;
    ou_brief_pass(0, NULL, rec, huge);
    subtest(rec[0][OU_NOHC] == W * H && rec[0][OU_PHC] == W * H && rec[0][OU_XMIN] == 0 &&
                rec[0][OU_XMAX] == W - 1 && rec[0][OU_YMIN] == 0 && rec[0][OU_YMAX] == H - 1,
            "huge-coordinates-1e6");
    /* At +-1e30 Mesa's clipper loses precision (softpipe covers 1536 of the
     * 4096 pixels in GL_RENDER too); the unit must agree with GL_RENDER. */
    huge_scale = 1e30f;
    glDepthFunc(GL_LESS);
    expected = render_changed_pixels(huge);
    ou_brief_pass(0, NULL, rec, huge);
    if (rec[0][OU_NOHC] != expected)
        printf("1e30: NOHC %u, GL_RENDER changes %u pixels\n", rec[0][OU_NOHC], expected);
    subtest(expected > 0 && rec[0][OU_NOHC] == expected && rec[0][OU_PHC] == expected, "huge-coordinates-1e30");

    ou_brief_pass(0, NULL, rec, tri_zero_area);
    subtest(rec[0][OU_NOHC] == 0 && rec[0][OU_PHC] == 0, "zero-area");
    ou_brief_pass(0, NULL, rec, tri_misses_centres);
    ok = rec[0][OU_NOHC] == 0 && rec[0][OU_PHC] == 0;
    ou_brief_pass(0, NULL, rec, tri_one_centre);
    ok = ok && rec[0][OU_NOHC] == 1 && rec[0][OU_PHC] == 1 && rec[0][OU_XMIN] == 10 && rec[0][OU_YMIN] == 10;
    subtest(ok, "sub-pixel");

    piglit_report_result(result);
}
