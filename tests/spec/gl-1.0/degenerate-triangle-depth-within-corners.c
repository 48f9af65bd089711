/* SPDX-License-Identifier: MIT */
/*
 * A fragment of a triangle takes the depth interpolated from its corners'
 * window depths with barycentric weights that are not negative and sum to
 * one (OpenGL 4.6, section 14.6.1, equation 14.9 with z in place of f), so
 * it lies between the least and the greatest of them, also for a triangle
 * whose corners are nearly collinear: such a triangle may cover a pixel
 * centre or none, but not with a depth from elsewhere.
 *
 * A 256 x 256 framebuffer, a perspective projection (near 0.025, far 50,
 * the planes of a walkthrough's camera 5 to 15 units away), the depth test
 * on (LESS over a cleared 1.0), 2,000 triangles drawn one at a time: the
 * corners a and b at random, the third at a random point of the segment ab
 * rounded to float, so that its distance from the line is float's rounding
 * of the coordinates (up to a few 1e-7 of them). After each, the depth of
 * every written pixel (read back as a float) must lie within the corners'
 * window depths, computed in double from the same matrices, widened by
 * 2^-16: above the float rounding of GL's transform (a few 2^-24 at depths
 * near 1) and the 24-bit depth buffer's step (2^-24), far below a depth
 * taken from outside the corners (llvmpipe wrote 0 for corners at 0.996,
 * found by occu's walkthrough on OpenArena's oa_thor, a level compiler's
 * T-junction fix).
 *
 * The corners are random from a fixed seed (an xorshift of its own, so that
 * every C library draws the same triangles).
 */
#include <stdint.h>
#include <stdio.h>

#include "piglit-util-gl.h"

enum { S = 256, TRIANGLES = 2000 };
static const double near_plane = 0.025, far_plane = 50.0, half_width = 0.0145;

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = S;
    config.window_height = S;
    config.window_visual = PIGLIT_GL_VISUAL_RGBA | PIGLIT_GL_VISUAL_DEPTH;
    config.khr_no_error_support = PIGLIT_NO_ERRORS;

PIGLIT_GL_TEST_CONFIG_END

static uint64_t state = 0x9e3779b97f4a7c15ull;

static double
uniform(void)
{
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return (double)(state >> 11) / (double)(1ull << 53);
}

static double
min3(double a, double b, double c)
{
    return a < b ? (a < c ? a : c) : (b < c ? b : c);
}

static double
max3(double a, double b, double c)
{
    return a > b ? (a > c ? a : c) : (b > c ? b : c);
}

/* Window depth of an eye-space point on the view axis's z (glFrustum,
 * depth range [0, 1]). */
static double
window_depth(double z_eye)
{
    const double n = near_plane, f = far_plane;
    const double z_clip = -(f + n) / (f - n) * z_eye - 2.0 * f * n / (f - n);
    return 0.5 * z_clip / -z_eye + 0.5;
}

enum piglit_result
piglit_display(void)
{
    /* piglit_init reports the result. */
    return PIGLIT_FAIL;
}

void
piglit_init(int argc, char **argv)
{
    static float depths[S * S];
    const double tolerance = 1.0 / (1 << 16);
    unsigned drawn = 0, wrong = 0;

    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-half_width, half_width, -half_width, half_width, near_plane, far_plane);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);

    for (int t = 0; t < TRIANGLES; t++) {
        double a[3], b[3];
        for (int i = 0; i < 2; i++) {
            a[i] = uniform() * 8.0 - 4.0;
            b[i] = uniform() * 8.0 - 4.0;
        }
        a[2] = -5.0 - uniform() * 10.0;
        b[2] = -5.0 - uniform() * 10.0;
        const double s = uniform();
        float c[3];
        for (int i = 0; i < 3; i++)
            c[i] = (float)(a[i] + s * (b[i] - a[i]));

        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glBegin(GL_TRIANGLES);
        glVertex3d(a[0], a[1], a[2]);
        glVertex3d(b[0], b[1], b[2]);
        glVertex3f(c[0], c[1], c[2]);
        glEnd();
        glReadPixels(0, 0, S, S, GL_DEPTH_COMPONENT, GL_FLOAT, depths);

        const double za = window_depth(a[2]), zb = window_depth(b[2]), zc = window_depth(c[2]);
        const double lo = min3(za, zb, zc) - tolerance;
        const double hi = max3(za, zb, zc) + tolerance;
        for (int p = 0; p < S * S; p++) {
            if (depths[p] == 1.0f)
                continue;
            drawn++;
            if (depths[p] < lo || depths[p] > hi) {
                if (wrong++ < 4)
                    printf("triangle %d, pixel (%d, %d): depth %.9g, corners' depths %.9g to %.9g\n",
                           t, p % S, p / S, depths[p], lo + tolerance, hi - tolerance);
            }
        }
    }
    printf("%u fragments written, %u outside their corners' depths\n", drawn, wrong);
    piglit_report_result(wrong == 0 && piglit_check_gl_error(GL_NO_ERROR) ? PIGLIT_PASS : PIGLIT_FAIL);
}
