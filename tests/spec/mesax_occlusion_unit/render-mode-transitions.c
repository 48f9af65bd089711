/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: transitions between the occlusion modes and
 * RENDER, SELECT and FEEDBACK (spec issue 9). Leaving an occlusion mode
 * for any mode writes its records; leaving SELECT or FEEDBACK for an
 * occlusion mode returns what it always returned; entering an occlusion
 * mode from one ends the first pass and starts a new one.
 */
#include "ou_util.h"

#define W 32
#define H 32



static GLint
mode(void)
{
    GLint m = 0;
    glGetIntegerv(GL_RENDER_MODE, &m);
    return m;
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
    GLuint select_buffer[64], record[64];
    GLfloat feedback[256];
    GLuint *buffers[1] = {record};
    GLsizei size = 64;
    glDisable(GL_DEPTH_TEST);
    glSelectBuffer(64, select_buffer);
    glFeedbackBuffer(256, GL_3D, feedback);
    OcclusionBuffersMESAX(1, &size, buffers);

    /* SELECT -> BRIEF: SELECT's hit count is returned. */
    glRenderMode(GL_SELECT);
    glInitNames();
    glPushName(7);
    ou_rect(0, 0, 4, 4, 0.5f);
    ou_fill(record, 64);
    GLint hits = glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    subtest(hits == 1 && select_buffer[3] == 7 && mode() == GL_BRIEF_OCCLUSION_MESAX && record[0] == OU_SENTINEL,
            "select-to-brief-returns-hits");

    /* BRIEF -> FEEDBACK: the record is written, 0 overflows returned. */
    ou_rect(0, 0, 4, 4, 0.5f);
    GLint r = glRenderMode(GL_FEEDBACK);
    subtest(r == 0 && record[OU_NOHC] == 16 && record[OU_PHC] == 16 && mode() == GL_FEEDBACK,
            "brief-to-feedback-writes-record");

    /* FEEDBACK -> VERBOSE: feedback's count is returned. */
    ou_rect(0, 0, 4, 4, 0.5f);
    ou_fill(record, 64);
    GLint values = glRenderMode(GL_VERBOSE_OCCLUSION_MESAX);
    subtest(values > 0 && feedback[0] == GL_POLYGON_TOKEN && mode() == GL_VERBOSE_OCCLUSION_MESAX,
            "feedback-to-verbose-returns-count");

    /* VERBOSE -> BRIEF: the first pass ends (its record written), a new one starts. */
    ou_rect(0, 0, 2, 2, 0.5f);
    r = glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    bool first_pass = r == 0 && record[OU_NOHC] == 4 && record[8] <= 1 && record[9] <= 1;
    ou_fill(record, 64);
    ou_rect(0, 0, 3, 3, 0.5f);
    r = glRenderMode(GL_SELECT);
    subtest(first_pass && r == 0 && record[OU_NOHC] == 9 && record[8] == OU_SENTINEL && mode() == GL_SELECT,
            "verbose-to-brief-restarts-pass");

    /* SELECT -> RENDER as always, and GL_RENDER draws again. */
    hits = glRenderMode(GL_RENDER);
    subtest(hits == 0 && mode() == GL_RENDER && piglit_check_gl_error(GL_NO_ERROR), "select-to-render");

    piglit_report_result(result);
}
