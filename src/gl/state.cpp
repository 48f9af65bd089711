// SPDX-License-Identifier: MIT
#include "gl/state.h"

#include <glm/gtc/type_ptr.hpp>

namespace occu::gl {

MatrixScope::MatrixScope()
{
    glMatrixMode(GL_PROJECTION);
    glPushMatrix();
    glMatrixMode(GL_MODELVIEW);
    glPushMatrix();
}

MatrixScope::~MatrixScope()
{
    glMatrixMode(GL_PROJECTION);
    glPopMatrix();
    glMatrixMode(GL_MODELVIEW);
    glPopMatrix();
}

void load_camera(const Camera &camera)
{
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixf(glm::value_ptr(camera.projection()));
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixf(glm::value_ptr(camera.view()));
}

}  // namespace occu::gl
