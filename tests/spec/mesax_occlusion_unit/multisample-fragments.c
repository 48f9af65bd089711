/*
 * GL_MESAX_occlusion_unit in a multisampled framebuffer counts fragments,
 * not samples (section 5.X): a fragment with at least one covered sample
 * counts in PHC, with at least one sample passing the tests in NOHC. A 4x
 * framebuffer object, a 16 x 16 rectangle, and an occluder in front of the
 * left half of the window. The fragments the rectangle has are measured,
 * not assumed: the pixels whose resolved colour it changes when drawn
 * in GL_RENDER (a pixel with any covered sample changes), as the
 * driver's sample positions and edge rules place them.
 *
 * Subtests:
 *   whole-rectangle-counts-fragments    NOHC = PHC = the pixels it changes
 *   depth-test-applies-per-fragment     behind the occluder: PHC as before,
 *                                       NOHC the changed pixels right of it
 *
 * softpipe has no multisampling (GL_MAX_SAMPLES below 4): there the test
 * skips, the one driver property it cannot have.
 */
#include "ou_util.h"

#define S 32

static GLuint
pass(float z)
{
    GLuint record[8];
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {8};
    OcclusionBuffersMESAX(1, sizes, buffers);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    ou_rect(8, 8, 24, 24, z);
    glRenderMode(GL_RENDER);
    printf("NOHC %u PHC %u\n", record[OU_NOHC], record[OU_PHC]);
    return record[OU_NOHC] | (GLuint)record[OU_PHC] << 16;
}

int main(int argc, char **argv)
{
    ou_init(argc, argv, S, S);
    GLint max_samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    if (max_samples < 4) {
        printf("%s has no 4x multisampling (GL_MAX_SAMPLES %d)\n", (const char *)glGetString(GL_RENDERER), max_samples);
        piglit_report_result(PIGLIT_SKIP);
    }
    const struct ou_fbo_functions f = ou_fbo_functions();
    GLuint rb[2];
    const GLuint fbo = ou_make_fbo(&f, S, S, 4, true, rb);
    /* The rectangle's fragments: drawn in GL_RENDER over black, resolved
     * into a single-sample framebuffer, read back. */
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glColor3f(1, 1, 1);
    ou_rect(8, 8, 24, 24, 0.5f);
    f.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    f.BlitFramebuffer(0, 0, S, S, 0, 0, S, S, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    f.BindFramebuffer(GL_FRAMEBUFFER, 0);
    static GLubyte pixels[S * S * 4];
    glReadPixels(0, 0, S, S, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    GLuint fragments = 0, right_of_occluder = 0;
    for (int i = 0; i < S * S; ++i)
        if (pixels[4 * i]) {
            ++fragments;
            right_of_occluder += i % S >= 16;
        }
    f.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    printf("the rectangle changes %u pixels, %u right of x = 16\n", fragments, right_of_occluder);
    if (fragments < 256) {
        printf("fewer pixels than the rectangle's 256\n");
        piglit_report_result(PIGLIT_FAIL);
    }

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClear(GL_DEPTH_BUFFER_BIT);
    GLuint r = pass(0.5f);
    subtest((r & 0xffff) == fragments && (r >> 16) == fragments, "whole-rectangle-counts-fragments");

    ou_rect(0, 0, 16, S, 0.25f);   /* the occluder, drawn into depth */
    r = pass(0.5f);
    subtest((r & 0xffff) == right_of_occluder && (r >> 16) == fragments, "depth-test-applies-per-fragment");
    piglit_report_result(result);
}
