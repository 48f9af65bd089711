// SPDX-License-Identifier: MIT
// A framebuffer object of occu's own: RGBA8 colour and 24-bit depth with
// 8-bit stencil, for images a strategy or a preprocessing step draws for
// itself (occluder depth, ID buffers), so that it never touches the
// caller's framebuffer.
#pragma once

#include "gl/gl_headers.h"

namespace occu::gl {

class Framebuffer {
public:
    // Needs a current context with framebuffer objects (GL 3.0 or
    // ARB_framebuffer_object); throws std::runtime_error otherwise.
    Framebuffer(int width, int height);
    ~Framebuffer();
    Framebuffer(const Framebuffer &) = delete;
    Framebuffer &operator=(const Framebuffer &) = delete;

    int width() const { return width_; }
    int height() const { return height_; }
    // Reallocates its buffers when the size differs (contents undefined).
    void resize(int width, int height);

    // Binds the framebuffer for drawing and reading with a viewport over
    // all of it; the previous bindings and viewport come back at the end
    // of the scope.
    class Bind {
    public:
        explicit Bind(const Framebuffer &framebuffer);
        ~Bind();
        Bind(const Bind &) = delete;
        Bind &operator=(const Bind &) = delete;

    private:
        const Framebuffer &framebuffer_;
        GLint draw_ = 0, read_ = 0, viewport_[4] = {0, 0, 0, 0};
    };

private:
    void allocate();
    int width_, height_;
    GLuint framebuffer_ = 0, colour_ = 0, depth_ = 0;
};

}  // namespace occu::gl
