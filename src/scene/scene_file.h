// User scenes from files (OBJ, glTF and the other formats assimp reads).
#pragma once

#include <string>

#include "scene/scene.h"

namespace occu {

// Loads every mesh of the file as triangles (polygons triangulated, normals
// generated where missing; node transforms applied). Throws
// std::runtime_error naming the file and assimp's reason when it cannot
// read it or it holds no triangles, and naming the file, mesh and vertex
// when a vertex coordinate is not finite (require_finite_vertices).
Scene load_scene(const std::string &path);

}  // namespace occu
