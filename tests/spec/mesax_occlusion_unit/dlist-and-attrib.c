/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit and display lists, glPushAttrib (spec issue 8):
 * ScissorsMESAX and OcclusionBuffersMESAX execute immediately even while a
 * list is compiled, and are not compiled into it: each list is called and
 * changes neither the tiles nor the buffers, while a glScissor compiled
 * next to them shows that the list ran. No attribute group, server or
 * client, saves the tiles or the buffers; PopAttrib(SCISSOR_BIT) restores the scissor box, which is the
 * default tile of the next pass.
 */
#include "ou_util.h"

#define W 32
#define H 32



static GLint
tile_count(void)
{
    GLint v = -1;
    glGetIntegerv(GL_OCCLUSION_TILE_COUNT_MESAX, &v);
    return v;
}

static bool
scissor_box_is(GLint x, GLint y, GLint w, GLint h)
{
    GLint box[4] = {-1, -1, -1, -1};
    glGetIntegerv(GL_SCISSOR_BOX, box);
    if (box[0] == x && box[1] == y && box[2] == w && box[3] == h)
        return true;
    printf("scissor box %d %d %d %d, expected %d %d %d %d: the list did not run\n", box[0], box[1], box[2], box[3], x,
           y, w, h);
    return false;
}

static void draw_all(void) { ou_rect(0, 0, W, H, 0.5f); }

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
    glDisable(GL_DEPTH_TEST);
    const GLint tiles[12] = {0, 0, 1, 1, 0, 0, 2, 2, 0, 0, 3, 3};

    /* Each list also holds a glScissor, which is compiled: after
     * glCallList the scissor box shows that the list was executed. */
    GLuint list = glGenLists(1);
    glNewList(list, GL_COMPILE);
    ScissorsMESAX(2, tiles);
    glScissor(1, 2, 3, 4);
    glEndList();
    subtest(tile_count() == 2 && piglit_check_gl_error(GL_NO_ERROR), "scissors-executes-while-compiling");
    ScissorsMESAX(0, NULL);
    glScissor(0, 0, W, H);
    glCallList(list);
    subtest(scissor_box_is(1, 2, 3, 4) && tile_count() == 0 && piglit_check_gl_error(GL_NO_ERROR),
            "scissors-not-compiled");
    glScissor(0, 0, W, H);

    /* Buffers set while compiling are in effect at once. */
    GLuint record[8], other[8];
    GLuint *buffers[1] = {record}, *other_buffers[1] = {other};
    GLsizei size = 8;
    GLuint list2 = glGenLists(1);
    glNewList(list2, GL_COMPILE);
    OcclusionBuffersMESAX(1, &size, buffers);
    glScissor(1, 2, 3, 4);
    glEndList();
    ou_fill(record, 8);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    bool entered = piglit_check_gl_error(GL_NO_ERROR);
    draw_all();
    glRenderMode(GL_RENDER);
    subtest(entered && record[OU_NOHC] == W * H, "buffers-execute-while-compiling");

    /* Calling the list sets no buffers: the next pass writes `other`. */
    OcclusionBuffersMESAX(1, &size, other_buffers);
    glScissor(0, 0, W, H);
    glCallList(list2);
    const bool called = scissor_box_is(1, 2, 3, 4);
    glScissor(0, 0, W, H);
    ou_fill(record, 8);
    ou_fill(other, 8);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    draw_all();
    glRenderMode(GL_RENDER);
    subtest(called && piglit_check_gl_error(GL_NO_ERROR) && other[OU_NOHC] == W * H && record[OU_NOHC] == OU_SENTINEL,
            "buffers-not-compiled");

    /* No attribute group holds the tiles. */
    glPushAttrib(GL_ALL_ATTRIB_BITS);
    ScissorsMESAX(3, tiles);
    glPopAttrib();
    subtest(tile_count() == 3, "push-pop-attrib-keeps-tiles");
    ScissorsMESAX(0, NULL);

    /* Nor the buffers: after PopAttrib the pass writes the buffer set
     * between PushAttrib and PopAttrib. */
    OcclusionBuffersMESAX(1, &size, buffers);
    glPushAttrib(GL_ALL_ATTRIB_BITS);
    glPushClientAttrib(GL_CLIENT_ALL_ATTRIB_BITS);
    OcclusionBuffersMESAX(1, &size, other_buffers);
    glPopClientAttrib();
    glPopAttrib();
    ou_fill(record, 8);
    ou_fill(other, 8);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
    draw_all();
    glRenderMode(GL_RENDER);
    subtest(piglit_check_gl_error(GL_NO_ERROR) && other[OU_NOHC] == W * H && record[OU_NOHC] == OU_SENTINEL,
            "push-pop-attrib-keeps-buffers");

    /* PopAttrib restores the scissor box: the default tile of the next pass. */
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 4, 4);
    glPushAttrib(GL_SCISSOR_BIT);
    glScissor(0, 0, 8, 8);
    glPopAttrib();
    GLuint rec[1][OU_BRIEF_SIZE];
    ou_brief_pass(0, NULL, rec, draw_all);
    glDisable(GL_SCISSOR_TEST);
    subtest(rec[0][OU_NOHC] == 16 && rec[0][OU_XMAX] == 3, "pop-attrib-scissor-is-default-tile");

    piglit_report_result(result);
}
