/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit's state is per context (spec section 5.X and
 * issue 23). Context A is the test's; context B shares A's objects
 * (ou_two_contexts.h) and renders into a buffer of the same size. Depth
 * tests are off: every fragment passes. The pass objects of
 * GL_MESAX_occlusion_unit_async: async-per-context-state.c.
 *
 * Subtests:
 *   share-group-shares-textures     sanity: a texture made in A is a texture in B
 *   tiles-per-context               tiles and buffers set in A are not B's, nor B's A's
 *   render-mode-per-context         while A is in a pass, B is in RENDER mode
 *   other-context-renders           B draws a 32 x 32 white rectangle into its buffer
 *                                   during A's pass, and binds framebuffers freely
 *   pass-counts-own-context-only    A's record counts A's 8 x 8 rectangle only
 *                                   (NOHC 64), not B's draw
 */
#include "ou_util.h"
#include "ou_two_contexts.h"

enum { S = 32 };

static struct ou_two_contexts c;

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
    c = ou_make_second_context(S);
    ou_make_b_current(&c);
    glViewport(0, 0, S, S);
    glMatrixMode(GL_PROJECTION);
    glOrtho(0, S, 0, S, 0, -1);
    glMatrixMode(GL_MODELVIEW);
    glDisable(GL_DEPTH_TEST);
    const GLint b_tiles[4] = {0, 0, 4, 4};
    ScissorsMESAX(1, b_tiles);
    ou_make_a_current(&c);
    glDisable(GL_DEPTH_TEST);

    /* The share group is real: what the extension's state does not share,
     * a texture does. */
    GLuint texture;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    ou_make_b_current(&c);
    const bool shared_texture = glIsTexture(texture) == GL_TRUE;
    ou_make_a_current(&c);
    subtest(shared_texture && piglit_check_gl_error(GL_NO_ERROR), "share-group-shares-textures");

    /* A's tiles and buffers. */
    const GLint a_tiles[8] = {0, 0, S, S, 0, 0, 16, 16};
    GLuint records[2][OU_BRIEF_SIZE];
    GLuint *buffers[2] = {records[0], records[1]};
    GLsizei sizes[2] = {OU_BRIEF_SIZE, OU_BRIEF_SIZE};
    ScissorsMESAX(2, a_tiles);
    OcclusionBuffersMESAX(2, sizes, buffers);
    const bool a_state = ou_get_integer(GL_OCCLUSION_TILE_COUNT_MESAX) == 2 &&
                         ou_get_integer(GL_OCCLUSION_BUFFER_COUNT_MESAX) == 2;
    ou_make_b_current(&c);
    const bool b_state = ou_get_integer(GL_OCCLUSION_TILE_COUNT_MESAX) == 1 &&
                         ou_get_integer(GL_OCCLUSION_BUFFER_COUNT_MESAX) == 0;
    ou_make_a_current(&c);
    if (!a_state || !b_state)
        printf("tile and buffer counts: A's %s, B's %s\n", a_state ? "right" : "wrong", b_state ? "right" : "wrong");
    subtest(a_state && b_state && piglit_check_gl_error(GL_NO_ERROR), "tiles-per-context");

    /* A's pass, with B drawing in the middle of it. */
    ou_fill(records[0], OU_BRIEF_SIZE);
    ou_fill(records[1], OU_BRIEF_SIZE);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    ou_rect(4, 4, 12, 12, 0.5f);
    glFlush();

    ou_make_b_current(&c);
    const GLint b_mode = ou_get_integer(GL_RENDER_MODE);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glColor4f(1, 1, 1, 1);
    ou_rect(0, 0, S, S, 0.5f);
    const struct ou_fbo_functions f = ou_fbo_functions();
    GLuint rb[2];
    const GLuint fbo = ou_make_fbo(&f, S, S, 0, false, rb);
    f.BindFramebuffer(GL_FRAMEBUFFER, 0);   /* B's own buffer, not the test's window */
    const bool b_bound = piglit_check_gl_error(GL_NO_ERROR) && fbo != 0;
    static const unsigned char white[4] = {255, 255, 255, 255};
    const bool b_drew = ou_probe_rect_rgba_ub(0, 0, S, S, white, 0);
    glFinish();

    ou_make_a_current(&c);
    const GLint a_mode = ou_get_integer(GL_RENDER_MODE);
    glRenderMode(GL_RENDER);
    if (b_mode != GL_RENDER || a_mode != GL_BRIEF_OCCLUSION_MESAX)
        printf("RENDER_MODE during A's pass: 0x%x in B, 0x%x in A\n", b_mode, a_mode);
    subtest(b_mode == GL_RENDER && a_mode == GL_BRIEF_OCCLUSION_MESAX, "render-mode-per-context");
    subtest(b_drew && b_bound, "other-context-renders");
    if (records[0][OU_NOHC] != 64 || records[0][OU_PHC] != 64 || records[1][OU_NOHC] != 64)
        printf("A's records: NOHC %u PHC %u, tile 1 NOHC %u; expected 64, 64, 64\n", records[0][OU_NOHC],
               records[0][OU_PHC], records[1][OU_NOHC]);
    subtest(records[0][OU_NOHC] == 64 && records[0][OU_PHC] == 64 && records[1][OU_NOHC] == 64 &&
                piglit_check_gl_error(GL_NO_ERROR),
            "pass-counts-own-context-only");
    ScissorsMESAX(0, NULL);

    ou_destroy_second_context(&c);
    piglit_report_result(result);
}
