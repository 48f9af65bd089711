/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit in a multisampled framebuffer counts fragments,
 * not samples (section 5.X): a fragment with at least one covered sample
 * counts in PHC, with at least one sample passing the tests in NOHC. A 4x
 * framebuffer object, a 16 x 16 rectangle drawn as two triangles, and an
 * occluder in front of the left half of the window.
 *
 * Each primitive has its own fragments (GL 4.6 section 14.3.1): where the
 * two triangles' shared diagonal crosses a pixel, each covers some of its
 * samples and each produces a fragment, so in a multisampled framebuffer
 * the rectangle has more fragments than it changes pixels (with one sample
 * per pixel the pixel's centre belongs to one triangle only). The
 * fragments are therefore measured per triangle, not assumed: the pixels
 * whose resolved colour each triangle alone changes when drawn in
 * GL_RENDER (a pixel with any covered sample changes), summed over the
 * two, as the driver's sample positions and edge rules place them.
 *
 * Subtests:
 *   whole-rectangle-counts-fragments    NOHC = PHC = the fragments measured
 *   depth-test-applies-per-fragment     behind the occluder: PHC as before,
 *                                       NOHC the fragments right of it
 *   samples-passed-counts-samples       a GL_SAMPLES_PASSED query inside
 *                                       the pass counts what it counts in
 *                                       GL_RENDER (samples, not fragments):
 *                                       exactly the samples right of the
 *                                       occluder (derived where it is checked)
 *
 * softpipe has no multisampling (GL_MAX_SAMPLES below 4): there the test
 * skips, the one driver property it cannot have.
 */
#include "ou_util.h"

#define S 32

static const float corners[4][2] = {{8, 8}, {24, 8}, {24, 24}, {8, 24}};

/* Triangle t of the rectangle: (0, 1, 2) or (0, 2, 3). */
static void
triangle(int t, float z)
{
    glBegin(GL_TRIANGLES);
    glVertex3f(corners[0][0], corners[0][1], z);
    glVertex3f(corners[1 + t][0], corners[1 + t][1], z);
    glVertex3f(corners[2 + t][0], corners[2 + t][1], z);
    glEnd();
}

static void
rectangle(float z)
{
    triangle(0, z);
    triangle(1, z);
}

static GLuint
pass(float z, GLuint *phc)
{
    GLuint record[OU_BRIEF_SIZE];
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    rectangle(z);
    glRenderMode(GL_RENDER);
    printf("NOHC %u PHC %u\n", record[OU_NOHC], record[OU_PHC]);
    *phc = record[OU_PHC];
    return record[OU_NOHC];
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
    GLint max_samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    if (max_samples < 4) {
        printf("%s has no 4x multisampling (GL_MAX_SAMPLES %d)\n", (const char *)glGetString(GL_RENDERER), max_samples);
        piglit_report_result(PIGLIT_SKIP);
    }
    const struct ou_fbo_functions f = ou_fbo_functions();
    GLuint rb[2];
    const GLuint fbo = ou_make_fbo(&f, S, S, 4, true, rb);

    /* Each triangle's fragments: drawn alone in GL_RENDER over black,
     * resolved into the single-sample window, read back. */
    GLuint fragments = 0, right_of_occluder = 0;
    glColor3f(1, 1, 1);
    for (int t = 0; t < 2; ++t) {
        f.BindFramebuffer(GL_FRAMEBUFFER, fbo);
        glClearColor(0, 0, 0, 0);
        glClear(GL_COLOR_BUFFER_BIT);
        triangle(t, 0.5f);
        f.BindFramebuffer(GL_DRAW_FRAMEBUFFER, piglit_winsys_fbo);
        f.BlitFramebuffer(0, 0, S, S, 0, 0, S, S, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        f.BindFramebuffer(GL_FRAMEBUFFER, piglit_winsys_fbo);
        static GLubyte pixels[S * S * 4];
        glReadPixels(0, 0, S, S, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
        for (int i = 0; i < S * S; ++i)
            if (pixels[4 * i]) {
                ++fragments;
                right_of_occluder += i % S >= 16;
            }
    }
    f.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    printf("the two triangles have %u fragments, %u right of x = 16\n", fragments, right_of_occluder);
    if (fragments < 256) {
        printf("fewer fragments than the rectangle's 256 pixels\n");
        piglit_report_result(PIGLIT_FAIL);
    }

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClear(GL_DEPTH_BUFFER_BIT);
    GLuint phc;
    GLuint nohc = pass(0.5f, &phc);
    subtest(nohc == fragments && phc == fragments, "whole-rectangle-counts-fragments");

    ou_rect(0, 0, 16, S, 0.25f);   /* the occluder, drawn into depth */
    nohc = pass(0.5f, &phc);
    subtest(nohc == right_of_occluder && phc == fragments, "depth-test-applies-per-fragment");

    /* Spec 4.1.7 edit: occlusion queries count as in RENDER mode. The
     * same draw against the same depth buffer, once in GL_RENDER and once
     * in a pass, must count exactly the samples that pass:
     * - the rectangle's edges (x 8 and 24, y 8 and 24) and the occluder's
     *   right edge (x 16) lie on pixel boundaries, and a sample position
     *   lies inside its pixel, never on its boundary, so every sample of the
     *   rectangle's pixels, and of those only, is inside the rectangle, and
     *   every sample of the pixels left of x = 16 is inside the occluder;
     * - a sample on the diagonal the two triangles share is covered by one
     *   of them, never both (GL 4.6 section 14.6.3, multisample
     *   rasterization takes the polygon rules at each sample point);
     * - LESS, the occluder's depth 0.25 against the rectangle's 0.5: the
     *   occluded samples fail, the others pass against the cleared 1.0.
     * So the count is the samples of the 8 x 16 pixels right of x = 16:
     * GL_SAMPLES of the framebuffer (4 asked for; the implementation may
     * give more) times 128. */
    PFNGLGENQUERIESPROC GenQueries = glGenQueries;
    PFNGLBEGINQUERYPROC BeginQuery = glBeginQuery;
    PFNGLENDQUERYPROC EndQuery = glEndQuery;
    PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv =
        glGetQueryObjectuiv;
    GLuint query, samples[2];
    GenQueries(1, &query);
    GLuint record[OU_BRIEF_SIZE];
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    for (int in_pass = 0; in_pass < 2; ++in_pass) {
        glClear(GL_DEPTH_BUFFER_BIT);
        ou_rect(0, 0, 16, S, 0.25f);
        if (in_pass) {
            OcclusionBuffersMESAX(1, sizes, buffers);
            glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
        }
        BeginQuery(GL_SAMPLES_PASSED, query);
        rectangle(0.5f);
        EndQuery(GL_SAMPLES_PASSED);
        if (in_pass)
            glRenderMode(GL_RENDER);
        GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples[in_pass]);
    }
    GLint samples_per_pixel = 0;
    glGetIntegerv(GL_SAMPLES, &samples_per_pixel);
    const GLuint expected = (GLuint)samples_per_pixel * 8 * 16;
    printf("GL_SAMPLES_PASSED: %u in GL_RENDER, %u in a pass, expected %u (%d samples a pixel, 8 x 16 pixels)\n",
           samples[0], samples[1], expected, samples_per_pixel);
    subtest(samples_per_pixel >= 4 && samples[0] == expected && samples[1] == expected,
            "samples-passed-counts-samples");
    piglit_report_result(result);
}
