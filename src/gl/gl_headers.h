// SPDX-License-Identifier: MIT
// The one place that includes GL headers, so that every file sees the same
// prototypes and extension typedefs. Entry points beyond GL 1.1 are fetched
// with get_proc_address, never linked directly.
#pragma once

#include <GL/gl.h>
#include <GL/glext.h>

namespace occu::gl {

using Proc = void (*)();

// Entry point of the GL implementation the current context belongs to.
Proc get_proc_address(const char *name);

}  // namespace occu::gl
