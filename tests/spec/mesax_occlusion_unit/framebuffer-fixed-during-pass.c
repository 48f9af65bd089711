/* SPDX-License-Identifier: MIT */
/*
 * GL_MESAX_occlusion_unit: the draw framebuffer of an occlusion pass is
 * fixed for the pass (Errors): binding another framebuffer for drawing,
 * attaching an image to the draw framebuffer, reallocating a renderbuffer
 * attached to it, or deleting it or an image attached to it generates
 * INVALID_OPERATION and changes nothing, so the tiles keep counting the framebuffer they were set for.
 * Binding for reading, or binding the draw framebuffer again, is allowed;
 * after the pass all of these work again.
 *
 * Subtests:
 *   bind-other-draw-invalid-operation   f.BindFramebuffer(DRAW or FRAMEBUFFER)
 *                                       of another object; the binding stays
 *                                       and a 8 x 8 draw counts 64
 *   bind-read-allowed                   f.BindFramebuffer(READ) of another
 *   bind-same-draw-allowed              the draw framebuffer again
 *   attach-renderbuffer-invalid-operation
 *   attach-texture-invalid-operation
 *   reallocate-attached-invalid-operation  RenderbufferStorage of the
 *                                       attached colour buffer; its width stays
 *   delete-draw-framebuffer-invalid-operation  DeleteFramebuffers of the draw
 *                                       framebuffer: the name stays a
 *                                       framebuffer and bound (during and
 *                                       after the pass), a draw counts 64
 *   delete-list-deletes-none            DeleteFramebuffers of another object
 *                                       and the draw framebuffer: the error,
 *                                       and neither is deleted
 *   all-allowed-after-pass
 *   delete-attached-renderbuffer-invalid-operation  DeleteRenderbuffers of the
 *                                       attached depth buffer (cleared to 0):
 *                                       the error, it stays attached and a quad
 *                                       at depth 0.5 stays hidden (NOHC 0)
 *   delete-attached-texture-invalid-operation  DeleteTextures of the texture
 *                                       attached as colour 1: the error, it
 *                                       stays a texture and attached
 *   delete-allowed-after-pass           both deletions work after the pass
 */
#include "ou_util.h"

static struct ou_fbo_functions f;
static GLuint fbo[2], colour[1], depth, texture;
static GLuint record[8];

static void
begin_pass(void)
{
    GLuint *buffers[1] = {record};
    GLsizei sizes[1] = {8};
    const GLint tile[4] = {0, 0, 32, 32};
    OcclusionBuffersMESAX(1, sizes, buffers);
    ScissorsMESAX(1, tile);
    glRenderMode(GL_BRIEF_OCCLUSION_MESAX);
}

static GLuint
end_pass(void)
{
    glRenderMode(GL_RENDER);
    ScissorsMESAX(0, NULL);
    return record[OU_NOHC];
}

static GLint
draw_binding(void)
{
    GLint b = -1;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &b);
    return b;
}

PIGLIT_GL_TEST_CONFIG_BEGIN

    config.supports_gl_compat_version = 10;
    config.window_width = 32;
    config.window_height = 32;
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
    ou_init();
    f = ou_fbo_functions();
    PFNGLGETRENDERBUFFERPARAMETERIVPROC GetRenderbufferParameteriv =
        glGetRenderbufferParameteriv;
    glDisable(GL_DEPTH_TEST);
    GLuint unused[2];
    fbo[1] = ou_make_fbo(&f, 32, 32, 0, false, unused);
    fbo[0] = ou_make_fbo(&f, 32, 32, 0, false, unused);   /* bound; no depth attached */
    colour[0] = unused[0];
    f.GenRenderbuffers(1, &depth);
    f.BindRenderbuffer(GL_RENDERBUFFER, depth);
    f.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, 32, 32);
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 32, 32, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    while (glGetError() != GL_NO_ERROR)
        ;

    begin_pass();
    f.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo[1]);
    bool ok = glGetError() == GL_INVALID_OPERATION;
    f.BindFramebuffer(GL_FRAMEBUFFER, fbo[1]);
    ok = ok && glGetError() == GL_INVALID_OPERATION && draw_binding() == (GLint)fbo[0];
    ou_rect(4, 4, 12, 12, 0.5f);
    subtest(end_pass() == 64 && ok, "bind-other-draw-invalid-operation");

    begin_pass();
    f.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo[1]);
    ok = glGetError() == GL_NO_ERROR;
    f.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo[0]);
    end_pass();
    subtest(ok, "bind-read-allowed");

    begin_pass();
    f.BindFramebuffer(GL_FRAMEBUFFER, fbo[0]);
    ok = glGetError() == GL_NO_ERROR;
    ou_rect(4, 4, 12, 12, 0.5f);
    subtest(end_pass() == 64 && ok, "bind-same-draw-allowed");

    begin_pass();
    f.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    GLint type = -1;
    PFNGLGETFRAMEBUFFERATTACHMENTPARAMETERIVPROC GetAttachment = glGetFramebufferAttachmentParameteriv;
    ok = glGetError() == GL_INVALID_OPERATION;
    end_pass();
    GetAttachment(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    subtest(ok && type == GL_NONE, "attach-renderbuffer-invalid-operation");

    begin_pass();
    f.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, texture, 0);
    ok = glGetError() == GL_INVALID_OPERATION;
    end_pass();
    GetAttachment(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    subtest(ok && type == GL_NONE, "attach-texture-invalid-operation");

    begin_pass();
    f.BindRenderbuffer(GL_RENDERBUFFER, colour[0]);
    f.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 64, 64);
    ok = glGetError() == GL_INVALID_OPERATION;
    ou_rect(0, 0, 32, 32, 0.5f);
    const GLuint whole = end_pass();
    GLint width = 0;
    GetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_WIDTH, &width);
    subtest(ok && width == 32 && whole == 32 * 32, "reallocate-attached-invalid-operation");

    /* An error changes no state (Errors): the name is not deleted either. */
    PFNGLDELETEFRAMEBUFFERSPROC DeleteFramebuffers =
        glDeleteFramebuffers;
    PFNGLISFRAMEBUFFERPROC IsFramebuffer = glIsFramebuffer;
    begin_pass();
    DeleteFramebuffers(1, &fbo[0]);
    ok = glGetError() == GL_INVALID_OPERATION;
    const bool kept_in_pass = IsFramebuffer(fbo[0]) && draw_binding() == (GLint)fbo[0];
    ou_rect(4, 4, 12, 12, 0.5f);
    const GLuint counted = end_pass();
    const bool kept_after = IsFramebuffer(fbo[0]) && draw_binding() == (GLint)fbo[0];
    if (!kept_in_pass || !kept_after)
        printf("after DeleteFramebuffers of the draw framebuffer %u: IsFramebuffer %d, draw binding %d\n", fbo[0],
               IsFramebuffer(fbo[0]), draw_binding());
    subtest(ok && kept_in_pass && kept_after && counted == 64 && glGetError() == GL_NO_ERROR,
            "delete-draw-framebuffer-invalid-operation");

    begin_pass();
    const GLuint both[2] = {fbo[1], fbo[0]};
    DeleteFramebuffers(2, both);
    ok = glGetError() == GL_INVALID_OPERATION;
    end_pass();
    subtest(ok && IsFramebuffer(fbo[0]) && IsFramebuffer(fbo[1]) && draw_binding() == (GLint)fbo[0],
            "delete-list-deletes-none");

    f.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    f.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, texture, 0);
    f.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 32, 32);
    f.BindFramebuffer(GL_FRAMEBUFFER, fbo[1]);
    subtest(glGetError() == GL_NO_ERROR && draw_binding() == (GLint)fbo[1], "all-allowed-after-pass");

    /* fbo[0] now has the depth renderbuffer and the texture (colour 1). */
    PFNGLDELETERENDERBUFFERSPROC DeleteRenderbuffers =
        glDeleteRenderbuffers;
    PFNGLISRENDERBUFFERPROC IsRenderbuffer = glIsRenderbuffer;
    f.BindFramebuffer(GL_FRAMEBUFFER, fbo[0]);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(0.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    begin_pass();
    DeleteRenderbuffers(1, &depth);
    ok = glGetError() == GL_INVALID_OPERATION;
    ou_rect(4, 4, 12, 12, 0.5f);
    const GLuint hidden = end_pass();
    GetAttachment(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (hidden != 0 || type != GL_RENDERBUFFER)
        printf("after DeleteRenderbuffers of the attached depth buffer: NOHC %u (expected 0), attachment type 0x%x\n",
               hidden, type);
    subtest(ok && hidden == 0 && type == GL_RENDERBUFFER && IsRenderbuffer(depth),
            "delete-attached-renderbuffer-invalid-operation");

    begin_pass();
    glDeleteTextures(1, &texture);
    ok = glGetError() == GL_INVALID_OPERATION;
    end_pass();
    GetAttachment(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    subtest(ok && type == GL_TEXTURE && glIsTexture(texture), "delete-attached-texture-invalid-operation");

    DeleteRenderbuffers(1, &depth);
    glDeleteTextures(1, &texture);
    ok = glGetError() == GL_NO_ERROR;
    GLint depth_type = -1;
    GetAttachment(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &depth_type);
    GetAttachment(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    subtest(ok && depth_type == GL_NONE && type == GL_NONE && !IsRenderbuffer(depth) && !glIsTexture(texture),
            "delete-allowed-after-pass");
    piglit_report_result(result);
}
