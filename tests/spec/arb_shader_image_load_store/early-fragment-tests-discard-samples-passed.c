/* SPDX-License-Identifier: MIT */
/*
 * With layout(early_fragment_tests) GL_SAMPLES_PASSED counts the samples
 * that pass the early tests, before the fragment shader, so a discard in
 * the shader removes nothing from the count (ARB_shader_image_load_store:
 * "the depth bounds test, stencil test, depth buffer test, and occlusion
 * query sample counting operations are performed prior to fragment shader
 * execution"; OpenGL 4.6, section 14.9). That holds with no depth or
 * stencil test enabled, where every covered sample passes the early tests,
 * and per sample in a multisampled framebuffer.
 *
 * A 203 x 150 framebuffer (neither side a multiple of llvmpipe's 64-pixel
 * bins), depth cleared to 1; with the depth test, an occluder written to
 * depth alone at z 0.25 over columns 0..66, then the depth test LESS and
 * depth writes off. A framebuffer-sized rectangle at z 0.5 is drawn inside
 * a GL_SAMPLES_PASSED query with a shader with early fragment tests that
 * discards every odd column and writes white elsewhere.
 *
 * The expectations are computed from the geometry: a sample is covered by a
 * rectangle where its position (the pixel's centre single-sampled, the
 * positions GL_SAMPLE_POSITION reports multisampled) lies inside it, and
 * passes the depth test where the occluder does not cover it; the count is
 * the number of covered samples passing the depth test, the pixels written
 * (read back, resolved from the multisampled buffer) those of them in even
 * columns. Tolerance 0: counts are of whole samples, every edge lies on
 * pixel boundaries and no sample position on one (checked), and white and
 * black are exact.
 *
 * Subtests:
 *   discarded-samples-counted-depth-test            single-sampled, depth test on
 *   discarded-samples-counted-no-depth-test         single-sampled, depth and
 *                                                   stencil tests off
 *   discarded-samples-counted-depth-test-4x         a 4x framebuffer object
 *   discarded-samples-counted-no-depth-test-4x      the same, tests off
 * The 4x subtests skip where the GL has no 4x multisampling (GL_MAX_SAMPLES
 * below 4: softpipe).
 */
#include <stdio.h>

#include "piglit-util-gl.h"

enum { W = 203, H = 150, OCCLUDER_RIGHT = 67, MAX_POSITIONS = 32 };

static const char fragment_source[] =
    "#version 150 compatibility\n"
    "#extension GL_ARB_shader_image_load_store : require\n"
    "layout(early_fragment_tests) in;\n"
    "void main() {\n"
    "  if (mod(floor(gl_FragCoord.x), 2.0) == 1.0)\n"
    "    discard;\n"
    "  gl_FragColor = vec4(1.0);\n"
    "}\n";

static GLuint program;

static void
rect(float x0, float y0, float x1, float y1, float z)
{
    glBegin(GL_QUADS);
    glVertex3f(x0, y0, z);
    glVertex3f(x1, y0, z);
    glVertex3f(x1, y1, z);
    glVertex3f(x0, y1, z);
    glEnd();
}

/* The sample positions inside a pixel, in [0, 1]: the pixel's centre when
 * the bound framebuffer is single-sampled. */
static int
sample_positions(float positions[MAX_POSITIONS][2])
{
    GLint samples = 0;
    glGetIntegerv(GL_SAMPLES, &samples);
    if (samples == 0) {
        positions[0][0] = positions[0][1] = 0.5f;
        return 1;
    }
    if (samples > MAX_POSITIONS)
        return 0;
    for (int i = 0; i < samples; ++i)
        glGetMultisamplefv(GL_SAMPLE_POSITION, i, positions[i]);
    return samples;
}

/* Draws the occluder (with the depth test) and the discarding rectangle in
 * a GL_SAMPLES_PASSED query on the bound framebuffer, then reads the colour
 * back from `read_fbo`, resolved into it first when it is not the bound
 * one; returns whether the count and the pixels are those computed. */
static bool
check(const char *name, bool depth_test, GLuint draw_fbo, GLuint read_fbo)
{
    static GLubyte pixels[H][W][4];
    float positions[MAX_POSITIONS][2];
    GLuint query, samples_passed = 0xdeadbeefu;
    unsigned expected_samples = 0, wrong = 0;

    const int n = sample_positions(positions);
    if (n == 0) {
        printf("%s: more than %d samples\n", name, MAX_POSITIONS);
        return false;
    }
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glDisable(GL_STENCIL_TEST);
    if (depth_test) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        rect(0, 0, OCCLUDER_RIGHT, H, 0.25f);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthMask(GL_FALSE);
    } else {
        glDisable(GL_DEPTH_TEST);
    }
    glUseProgram(program);
    glGenQueries(1, &query);
    glBeginQuery(GL_SAMPLES_PASSED, query);
    rect(0, 0, W, H, 0.5f);
    glEndQuery(GL_SAMPLES_PASSED);
    glUseProgram(0);
    glDepthMask(GL_TRUE);
    glGetQueryObjectuiv(query, GL_QUERY_RESULT, &samples_passed);
    if (read_fbo != draw_fbo) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, read_fbo);
        glBlitFramebuffer(0, 0, W, H, 0, 0, W, H, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, read_fbo);
    glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo);
    const bool no_error = piglit_check_gl_error(GL_NO_ERROR);

    for (int y = 0; y < H; ++y) {
        for (int x = 0; x < W; ++x) {
            unsigned passing = 0;
            for (int i = 0; i < n; ++i) {
                const float sx = x + positions[i][0], sy = y + positions[i][1];
                const bool covered = sx > 0 && sx < W && sy > 0 && sy < H;
                const bool occluded = depth_test && sx < OCCLUDER_RIGHT;
                passing += covered && !occluded;
            }
            expected_samples += passing;
            /* Every sample of a kept pixel passes (no position lies on an
             * edge, checked below), so the resolved colour is white. */
            const bool expected = passing > 0 && x % 2 == 0;
            const bool written = pixels[y][x][0] != 0;
            if (written != expected && wrong++ == 0)
                printf("%s: pixel (%d, %d) %s, expected %s\n", name, x, y, written ? "written" : "not written",
                       expected ? "written" : "not");
        }
    }
    bool on_edge = false;
    for (int i = 0; i < n; ++i)
        on_edge = on_edge || positions[i][0] <= 0 || positions[i][0] >= 1 || positions[i][1] <= 0 ||
                  positions[i][1] >= 1;
    if (on_edge)
        printf("%s: a sample position lies on a pixel's edge; the expectations assume none does\n", name);
    if (samples_passed != expected_samples)
        printf("%s: GL_SAMPLES_PASSED %u, expected %u (%d samples a pixel)\n", name, samples_passed,
               expected_samples, n);
    if (wrong)
        printf("%s: %u pixels wrong\n", name, wrong);
    const bool ok = !on_edge && samples_passed == expected_samples && wrong == 0 && no_error;
    piglit_report_subtest_result(ok ? PIGLIT_PASS : PIGLIT_FAIL, "%s", name);
    return ok;
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 32;
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
    bool ok = true;

    /* layout(early_fragment_tests) is ARB_shader_image_load_store's. */
    piglit_require_extension("GL_ARB_shader_image_load_store");
    program = piglit_build_simple_program(NULL, fragment_source);

    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, W, 0, H, 0, -1);   /* object z is window z */
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);

    ok = check("discarded-samples-counted-depth-test", true, piglit_winsys_fbo, piglit_winsys_fbo) && ok;
    ok = check("discarded-samples-counted-no-depth-test", false, piglit_winsys_fbo, piglit_winsys_fbo) && ok;

    GLint max_samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    if (max_samples < 4) {
        printf("%s has no 4x multisampling (GL_MAX_SAMPLES %d)\n", (const char *)glGetString(GL_RENDERER),
               max_samples);
        piglit_report_subtest_result(PIGLIT_SKIP, "discarded-samples-counted-depth-test-4x");
        piglit_report_subtest_result(PIGLIT_SKIP, "discarded-samples-counted-no-depth-test-4x");
        piglit_report_result(ok ? PIGLIT_PASS : PIGLIT_FAIL);
    }
    GLuint fbo, rb[2];
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(2, rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, 4, GL_RGBA8, W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, 4, GL_DEPTH24_STENCIL8, W, H);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        printf("the 4x framebuffer object is not complete\n");
        piglit_report_subtest_result(PIGLIT_FAIL, "discarded-samples-counted-depth-test-4x");
        piglit_report_subtest_result(PIGLIT_FAIL, "discarded-samples-counted-no-depth-test-4x");
        piglit_report_result(PIGLIT_FAIL);
    }
    glEnable(GL_MULTISAMPLE);
    ok = check("discarded-samples-counted-depth-test-4x", true, fbo, piglit_winsys_fbo) && ok;
    ok = check("discarded-samples-counted-no-depth-test-4x", false, fbo, piglit_winsys_fbo) && ok;
    glBindFramebuffer(GL_FRAMEBUFFER, piglit_winsys_fbo);
    piglit_report_result(ok ? PIGLIT_PASS : PIGLIT_FAIL);
}
