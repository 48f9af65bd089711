// SPDX-License-Identifier: MIT
// Which occlusion query answers "did any sample pass?", the one flag the
// HP occlusion test asks for (Scott, Olsen and Gannett 1998; Moeller and
// Haines, "VISUALIZE fx's hardware implementation"). GL_SAMPLES_PASSED
// (GL 1.5, ARB_occlusion_query) counts every sample; GL_ANY_SAMPLES_PASSED
// (GL 3.3, ARB_occlusion_query2) is the flag, and an implementation may
// stop counting once it is set; GL_ANY_SAMPLES_PASSED_CONSERVATIVE
// (GL 4.3, ARB_ES3_compatibility) may also answer true where no sample
// passed (a cheaper, coarser test), never false where one did, so a box it
// finds hidden is hidden.
#pragma once

#include <string>
#include <vector>

#include "gl/gl_headers.h"

namespace occu::gl {

// The cheapest of the three a context of GL version major.minor with
// `extensions` offers: the conservative flag, else the exact flag, else
// the count.
GLenum boolean_occlusion_query_target(int major, int minor, const std::vector<std::string> &extensions);

// The same for the current context.
GLenum boolean_occlusion_query_target();

// GL 1.5's occlusion query entry points (ARB_occlusion_query), looked up
// once; load() throws std::runtime_error naming `user` where the context
// lacks any of them.
struct QueryFunctions {
    PFNGLGENQUERIESPROC GenQueries;
    PFNGLDELETEQUERIESPROC DeleteQueries;
    PFNGLBEGINQUERYPROC BeginQuery;
    PFNGLENDQUERYPROC EndQuery;
    PFNGLGETQUERYOBJECTUIVPROC GetQueryObjectuiv;

    static QueryFunctions load(const std::string &user);
};

}  // namespace occu::gl
