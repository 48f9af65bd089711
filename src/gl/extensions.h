// SPDX-License-Identifier: MIT
// Extension lookup in the two forms GL reports them: the space-separated
// GL_EXTENSIONS string of compatibility contexts, and glGetStringi lists.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace occu::gl {

// True when `name` is one whole entry of the space-separated `list`
// (GL_ARB_foo does not match inside GL_ARB_foo_bar).
bool extension_in_list(std::string_view list, std::string_view name);

// The extensions of the current context, whichever way it reports them.
std::vector<std::string> current_extensions();

// True when the current context advertises `name`.
bool has_extension(std::string_view name);

}  // namespace occu::gl
