/* SPDX-License-Identifier: MIT */
/*
 * The harness itself: a context made under GALLIUM_DRIVER=<d> renders with
 * driver <d>, and window coordinates have OpenGL's bottom-left origin in the
 * colour buffer that glReadPixels returns.
 *
 * Subtests:
 *   renderer-names-driver   GL_RENDERER contains $GALLIUM_DRIVER (skip when unset)
 *   scissored-clear         a scissored clear changes exactly its rectangle (tolerance 0)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "piglit-util-gl.h"
/* ou_probe_rect_rgba_ub and the test's result. */
#include "ou_util.h"

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = 64;
    config.window_height = 48;
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
    result = PIGLIT_SKIP;

    const char *wanted = getenv("GALLIUM_DRIVER");
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    enum piglit_result r = PIGLIT_SKIP;
    if (wanted && *wanted) {
        r = renderer && strstr(renderer, wanted) ? PIGLIT_PASS : PIGLIT_FAIL;
        if (r == PIGLIT_FAIL)
            printf("GALLIUM_DRIVER=%s but GL_RENDERER is '%s'\n", wanted, renderer ? renderer : "(null)");
    }
    piglit_report_subtest_result(r, "renderer-names-driver");
    piglit_merge_result(&result, r);

    static const unsigned char black[4] = {0, 0, 0, 0}, red[4] = {255, 0, 0, 255};
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(5, 7, 11, 13);
    glClearColor(1, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    bool ok = ou_probe_rect_rgba_ub(5, 7, 11, 13, red, 0) &&
              ou_probe_rect_rgba_ub(0, 0, 64, 7, black, 0) &&
              ou_probe_rect_rgba_ub(0, 20, 64, 28, black, 0) &&
              ou_probe_rect_rgba_ub(0, 7, 5, 13, black, 0) &&
              ou_probe_rect_rgba_ub(16, 7, 48, 13, black, 0) &&
              piglit_check_gl_error(GL_NO_ERROR);
    r = ok ? PIGLIT_PASS : PIGLIT_FAIL;
    piglit_report_subtest_result(r, "scissored-clear");
    piglit_merge_result(&result, r);

    piglit_report_result(result);
}
