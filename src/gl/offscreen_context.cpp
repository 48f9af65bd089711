// SPDX-License-Identifier: MIT
#include "gl/offscreen_context.h"

#include <GL/osmesa.h>

#include <cstdlib>
#include <stdexcept>

#include "gl/gl_headers.h"

namespace occu::gl {

namespace {
// The driver of the first context this process made, if any.
const char *g_driver_in_use = nullptr;
}  // namespace

const char *driver_name(Driver d)
{
    return d == Driver::softpipe ? "softpipe" : "llvmpipe";
}

Driver parse_driver(const std::string &name)
{
    if (name == "softpipe")
        return Driver::softpipe;
    if (name == "llvmpipe")
        return Driver::llvmpipe;
    throw std::invalid_argument("unknown driver '" + name + "' (expected softpipe or llvmpipe)");
}

void select_driver(Driver d)
{
    const char *name = driver_name(d);
    if (g_driver_in_use && std::string(g_driver_in_use) != name)
        throw std::logic_error(std::string("this process already renders with ") + g_driver_in_use +
                               "; Mesa cannot switch to " + name + " (run another process)");
    setenv("GALLIUM_DRIVER", name, 1);
}

Proc get_proc_address(const char *name)
{
    return reinterpret_cast<Proc>(OSMesaGetProcAddress(name));
}

struct OffscreenContext::Handle {
    OSMesaContext ctx = nullptr;
};

OffscreenContext::OffscreenContext(int width, int height)
    : handle_(std::make_unique<Handle>()), width_(width), height_(height)
{
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        throw std::invalid_argument("off-screen size " + std::to_string(width) + "x" + std::to_string(height) +
                                    " is outside 1..16384");
    const int attribs[] = {
        OSMESA_FORMAT,       OSMESA_RGBA,
        OSMESA_DEPTH_BITS,   24,
        OSMESA_STENCIL_BITS, 8,
        OSMESA_PROFILE,      OSMESA_COMPAT_PROFILE,
        0,
    };
    handle_->ctx = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!handle_->ctx)
        throw std::runtime_error("OSMesaCreateContextAttribs failed (is libOSMesa occu's build?)");
    pixels_.assign(std::size_t(width) * std::size_t(height) * 4, 0);
    make_current();
    // OSMesa's default puts row 0 at the top; occu keeps OpenGL's convention.
    OSMesaPixelStore(OSMESA_Y_UP, 1);
    if (!g_driver_in_use) {
        const char *env = std::getenv("GALLIUM_DRIVER");
        g_driver_in_use = env && std::string(env) == "softpipe" ? "softpipe" : "llvmpipe";
    }
}

OffscreenContext::~OffscreenContext()
{
    if (handle_->ctx)
        OSMesaDestroyContext(handle_->ctx);
}

void OffscreenContext::make_current()
{
    if (!OSMesaMakeCurrent(handle_->ctx, pixels_.data(), GL_UNSIGNED_BYTE, width_, height_))
        throw std::runtime_error("OSMesaMakeCurrent failed");
}

std::string OffscreenContext::renderer() const
{
    const GLubyte *s = glGetString(GL_RENDERER);
    return s ? reinterpret_cast<const char *>(s) : "";
}

std::string OffscreenContext::version() const
{
    const GLubyte *s = glGetString(GL_VERSION);
    return s ? reinterpret_cast<const char *>(s) : "";
}

}  // namespace occu::gl
