// SPDX-License-Identifier: MIT
#include "gl/occlusion_query.h"

#include <algorithm>
#include <stdexcept>

#include "gl/extensions.h"

namespace occu::gl {

GLenum boolean_occlusion_query_target(int major, int minor, const std::vector<std::string> &extensions)
{
    const auto at_least = [&](int ma, int mi) { return major > ma || (major == ma && minor >= mi); };
    const auto has = [&](const char *name) {
        return std::find(extensions.begin(), extensions.end(), name) != extensions.end();
    };
    if (at_least(4, 3) || has("GL_ARB_ES3_compatibility"))
        return GL_ANY_SAMPLES_PASSED_CONSERVATIVE;
    if (at_least(3, 3) || has("GL_ARB_occlusion_query2"))
        return GL_ANY_SAMPLES_PASSED;
    return GL_SAMPLES_PASSED;
}

GLenum boolean_occlusion_query_target()
{
    // GL_MAJOR_VERSION is GL 3.0's; an older context reports an error and
    // is below 3.3 anyway.
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (glGetError() != GL_NO_ERROR)
        major = minor = 0;
    return boolean_occlusion_query_target(major, minor, current_extensions());
}

QueryFunctions QueryFunctions::load(const std::string &user)
{
    QueryFunctions f{
        reinterpret_cast<PFNGLGENQUERIESPROC>(get_proc_address("glGenQueries")),
        reinterpret_cast<PFNGLDELETEQUERIESPROC>(get_proc_address("glDeleteQueries")),
        reinterpret_cast<PFNGLBEGINQUERYPROC>(get_proc_address("glBeginQuery")),
        reinterpret_cast<PFNGLENDQUERYPROC>(get_proc_address("glEndQuery")),
        reinterpret_cast<PFNGLGETQUERYOBJECTUIVPROC>(get_proc_address("glGetQueryObjectuiv")),
    };
    if (!f.GenQueries || !f.DeleteQueries || !f.BeginQuery || !f.EndQuery || !f.GetQueryObjectuiv)
        throw std::runtime_error(user + " needs occlusion queries (GL 1.5 or ARB_occlusion_query)");
    return f;
}

}  // namespace occu::gl
