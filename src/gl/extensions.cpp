// SPDX-License-Identifier: MIT
#include "gl/extensions.h"

#include "gl/gl_headers.h"

namespace occu::gl {

bool extension_in_list(std::string_view list, std::string_view name)
{
    if (name.empty())
        return false;
    std::size_t pos = 0;
    while ((pos = list.find(name, pos)) != std::string_view::npos) {
        const bool starts = pos == 0 || list[pos - 1] == ' ';
        const std::size_t end = pos + name.size();
        const bool ends = end == list.size() || list[end] == ' ';
        if (starts && ends)
            return true;
        pos = end;
    }
    return false;
}

std::vector<std::string> current_extensions()
{
    std::vector<std::string> result;
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    if (glGetError() == GL_NO_ERROR && count > 0) {
        auto get_stringi = reinterpret_cast<PFNGLGETSTRINGIPROC>(get_proc_address("glGetStringi"));
        if (get_stringi) {
            for (GLint i = 0; i < count; ++i)
                result.emplace_back(reinterpret_cast<const char *>(get_stringi(GL_EXTENSIONS, GLuint(i))));
            return result;
        }
    }
    // GL 1.x/2.x: one string.
    const char *all = reinterpret_cast<const char *>(glGetString(GL_EXTENSIONS));
    std::string_view rest = all ? all : "";
    while (!rest.empty()) {
        const std::size_t space = rest.find(' ');
        if (space != 0)
            result.emplace_back(rest.substr(0, space));
        if (space == std::string_view::npos)
            break;
        rest.remove_prefix(space + 1);
    }
    return result;
}

bool has_extension(std::string_view name)
{
    for (const std::string &e : current_extensions())
        if (e == name)
            return true;
    return false;
}

}  // namespace occu::gl
