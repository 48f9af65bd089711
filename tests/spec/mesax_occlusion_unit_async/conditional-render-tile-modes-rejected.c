/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit_async: conditional rendering on a tile accepts
 * QUERY_WAIT and QUERY_NO_WAIT only; the by-region modes and the inverted
 * modes of ARB_conditional_render_inverted are not accepted (spec
 * MESAX_occlusion_unit_async, section 5.X.2, Errors and issue 17): each
 * generates INVALID_ENUM and begins nothing, so
 * EndConditionalRenderOcclusionTileMESAX then generates INVALID_OPERATION
 * and a draw after it is unconditional.
 *
 * The pass: one tile, the 32 x 32 window, with nothing drawn in it (NOHC
 * 0), so that a condition, had one begun, would discard the draw (and an
 * inverted one would draw it: the probe alone could not tell).
 *
 * Subtests: by-region-wait, by-region-no-wait, wait-inverted,
 * no-wait-inverted, by-region-wait-inverted, by-region-no-wait-inverted
 * (each: INVALID_ENUM, nothing begun, the red rectangle drawn).
 */
#include "ou_util.h"

#ifndef GL_QUERY_WAIT_INVERTED
#define GL_QUERY_WAIT_INVERTED 0x8E17
#define GL_QUERY_NO_WAIT_INVERTED 0x8E18
#endif
#ifndef GL_QUERY_BY_REGION_WAIT_INVERTED
#define GL_QUERY_BY_REGION_WAIT_INVERTED 0x8E19
#define GL_QUERY_BY_REGION_NO_WAIT_INVERTED 0x8E1A
#endif

enum { S = 32 };

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = S;
    config.window_height = S;
    config.window_visual = PIGLIT_GL_VISUAL_RGBA | PIGLIT_GL_VISUAL_DEPTH | PIGLIT_GL_VISUAL_STENCIL;
    config.khr_no_error_support = PIGLIT_HAS_ERRORS;

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
    const struct ou_async_functions a = ou_init_async();
    glDisable(GL_DEPTH_TEST);
    GLuint pass, record[OU_BRIEF_SIZE];
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {OU_BRIEF_SIZE};
    a.GenOcclusionPasses(1, &pass);
    OcclusionBuffersMESAX(1, sizes, buffers);
    a.BeginOcclusionPass(GL_BRIEF_OCCLUSION_MESAX, pass);
    a.EndOcclusionPass();

    static const struct {
        GLenum mode;
        const char *name;
    } modes[] = {
        {GL_QUERY_BY_REGION_WAIT, "by-region-wait"},
        {GL_QUERY_BY_REGION_NO_WAIT, "by-region-no-wait"},
        {GL_QUERY_WAIT_INVERTED, "wait-inverted"},
        {GL_QUERY_NO_WAIT_INVERTED, "no-wait-inverted"},
        {GL_QUERY_BY_REGION_WAIT_INVERTED, "by-region-wait-inverted"},
        {GL_QUERY_BY_REGION_NO_WAIT_INVERTED, "by-region-no-wait-inverted"},
    };
    static const unsigned char red[4] = {255, 0, 0, 255};
    for (unsigned i = 0; i < sizeof(modes) / sizeof(modes[0]); ++i) {
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        a.BeginConditionalRenderOcclusionTile(pass, 0, 0, 0.0f, modes[i].mode);
        const bool rejected = piglit_check_gl_error(GL_INVALID_ENUM);
        glColor4ub(255, 0, 0, 255);
        ou_rect(0, 0, S, S, 0.5f);
        const bool drawn = ou_probe_rect_rgba_ub(0, 0, S, S, red, 0);
        a.EndConditionalRenderOcclusionTile();
        const bool nothing_begun = piglit_check_gl_error(GL_INVALID_OPERATION);
        subtest(rejected && drawn && nothing_begun, modes[i].name);
    }
    a.DeleteOcclusionPasses(1, &pass);
    piglit_report_result(result);
}
