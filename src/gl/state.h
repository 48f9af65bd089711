// SPDX-License-Identifier: MIT
// GL state saved and restored by scope: the one way occu's library changes
// state it does not own. Every strategy, preprocessing step and renderer
// helper that sets depth, culling, polygon, colour or viewport state for
// its own drawing wraps it in a scope, so the caller finds its state as it
// left it (compatibility profile: the attribute stack).
#pragma once

#include "camera/camera.h"
#include "gl/gl_headers.h"

namespace occu::gl {

// glPushAttrib(mask) now, glPopAttrib() at the end of the scope.
class AttribScope {
public:
    explicit AttribScope(GLbitfield mask) { glPushAttrib(mask); }
    ~AttribScope() { glPopAttrib(); }
    AttribScope(const AttribScope &) = delete;
    AttribScope &operator=(const AttribScope &) = delete;
};

// The projection and modelview matrices, restored at the end of the scope.
class MatrixScope {
public:
    MatrixScope();
    ~MatrixScope();
    MatrixScope(const MatrixScope &) = delete;
    MatrixScope &operator=(const MatrixScope &) = delete;
};

// Loads the camera's projection and view into the fixed-function matrices.
void load_camera(const Camera &camera);

}  // namespace occu::gl
