// SPDX-License-Identifier: MIT
#include "gl/framebuffer.h"

#include <stdexcept>
#include <string>

namespace occu::gl {

namespace {

struct Entry {
    PFNGLGENFRAMEBUFFERSPROC GenFramebuffers;
    PFNGLDELETEFRAMEBUFFERSPROC DeleteFramebuffers;
    PFNGLBINDFRAMEBUFFERPROC BindFramebuffer;
    PFNGLGENRENDERBUFFERSPROC GenRenderbuffers;
    PFNGLDELETERENDERBUFFERSPROC DeleteRenderbuffers;
    PFNGLBINDRENDERBUFFERPROC BindRenderbuffer;
    PFNGLRENDERBUFFERSTORAGEPROC RenderbufferStorage;
    PFNGLFRAMEBUFFERRENDERBUFFERPROC FramebufferRenderbuffer;
    PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus;
};

const Entry &entry()
{
    static const Entry e = [] {
        Entry x{};
        x.GenFramebuffers = reinterpret_cast<PFNGLGENFRAMEBUFFERSPROC>(get_proc_address("glGenFramebuffers"));
        x.DeleteFramebuffers = reinterpret_cast<PFNGLDELETEFRAMEBUFFERSPROC>(get_proc_address("glDeleteFramebuffers"));
        x.BindFramebuffer = reinterpret_cast<PFNGLBINDFRAMEBUFFERPROC>(get_proc_address("glBindFramebuffer"));
        x.GenRenderbuffers = reinterpret_cast<PFNGLGENRENDERBUFFERSPROC>(get_proc_address("glGenRenderbuffers"));
        x.DeleteRenderbuffers =
            reinterpret_cast<PFNGLDELETERENDERBUFFERSPROC>(get_proc_address("glDeleteRenderbuffers"));
        x.BindRenderbuffer = reinterpret_cast<PFNGLBINDRENDERBUFFERPROC>(get_proc_address("glBindRenderbuffer"));
        x.RenderbufferStorage =
            reinterpret_cast<PFNGLRENDERBUFFERSTORAGEPROC>(get_proc_address("glRenderbufferStorage"));
        x.FramebufferRenderbuffer =
            reinterpret_cast<PFNGLFRAMEBUFFERRENDERBUFFERPROC>(get_proc_address("glFramebufferRenderbuffer"));
        x.CheckFramebufferStatus =
            reinterpret_cast<PFNGLCHECKFRAMEBUFFERSTATUSPROC>(get_proc_address("glCheckFramebufferStatus"));
        return x;
    }();
    if (!e.GenFramebuffers || !e.BindFramebuffer || !e.RenderbufferStorage || !e.CheckFramebufferStatus)
        throw std::runtime_error("this GL context has no framebuffer objects (GL 3.0 or ARB_framebuffer_object)");
    return e;
}

}  // namespace

Framebuffer::Framebuffer(int width, int height) : width_(width), height_(height)
{
    if (width < 1 || height < 1)
        throw std::invalid_argument("framebuffer of " + std::to_string(width) + "x" + std::to_string(height));
    const Entry &e = entry();
    e.GenFramebuffers(1, &framebuffer_);
    e.GenRenderbuffers(1, &colour_);
    e.GenRenderbuffers(1, &depth_);
    allocate();
}

Framebuffer::~Framebuffer()
{
    const Entry &e = entry();
    e.DeleteFramebuffers(1, &framebuffer_);
    e.DeleteRenderbuffers(1, &colour_);
    e.DeleteRenderbuffers(1, &depth_);
}

void Framebuffer::resize(int width, int height)
{
    if (width == width_ && height == height_)
        return;
    width_ = width;
    height_ = height;
    allocate();
}

void Framebuffer::allocate()
{
    const Entry &e = entry();
    GLint draw = 0, read = 0, renderbuffer = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
    glGetIntegerv(GL_RENDERBUFFER_BINDING, &renderbuffer);
    e.BindRenderbuffer(GL_RENDERBUFFER, colour_);
    e.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width_, height_);
    e.BindRenderbuffer(GL_RENDERBUFFER, depth_);
    e.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width_, height_);
    e.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    e.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
    e.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_);
    const GLenum status = e.CheckFramebufferStatus(GL_FRAMEBUFFER);
    e.BindRenderbuffer(GL_RENDERBUFFER, GLuint(renderbuffer));
    e.BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw));
    e.BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read));
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("framebuffer of " + std::to_string(width_) + "x" + std::to_string(height_) +
                                 " is incomplete (status " + std::to_string(status) + ")");
}

Framebuffer::Bind::Bind(const Framebuffer &framebuffer) : framebuffer_(framebuffer)
{
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_);
    glGetIntegerv(GL_VIEWPORT, viewport_);
    entry().BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.framebuffer_);
    glViewport(0, 0, framebuffer_.width_, framebuffer_.height_);
}

Framebuffer::Bind::~Bind()
{
    const Entry &e = entry();
    e.BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_));
    e.BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_));
    glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
}

}  // namespace occu::gl
