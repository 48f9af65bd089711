// SPDX-License-Identifier: MIT
// Off-screen OpenGL through OSMesa on occu's patched Mesa.
//
// Conventions: the colour buffer is RGBA8 in client memory, origin at the
// bottom-left as in OpenGL (row 0 is the bottom row); depth 24 bits, stencil 8.
// The context is a compatibility profile, because the Occlusion Unit lives
// beside GL_SELECT and GL_FEEDBACK in glRenderMode.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace occu::gl {

// Gallium software drivers occu runs on.
enum class Driver { softpipe, llvmpipe };

const char *driver_name(Driver d);
// Parses "softpipe" or "llvmpipe"; throws std::invalid_argument naming the input otherwise.
Driver parse_driver(const std::string &name);

// Mesa picks the gallium driver once per process, when the first OSMesa
// context is made, from GALLIUM_DRIVER. select_driver sets it; it throws
// std::logic_error if a context was already made with another driver.
void select_driver(Driver d);

class OffscreenContext {
public:
    // Makes a context of width x height and makes it current. Throws
    // std::runtime_error with OSMesa's failure when it cannot.
    OffscreenContext(int width, int height);
    ~OffscreenContext();
    OffscreenContext(const OffscreenContext &) = delete;
    OffscreenContext &operator=(const OffscreenContext &) = delete;

    void make_current();
    int width() const { return width_; }
    int height() const { return height_; }
    // Colour buffer, RGBA8, bottom row first.
    const std::uint8_t *pixels() const { return pixels_.data(); }
    std::uint8_t *pixels_mutable() { return pixels_.data(); }

    std::string renderer() const;
    std::string version() const;

private:
    struct Handle;
    std::unique_ptr<Handle> handle_;
    int width_, height_;
    std::vector<std::uint8_t> pixels_;
};

}  // namespace occu::gl
