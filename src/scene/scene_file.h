// SPDX-License-Identifier: MIT
// User scenes from files (OBJ, glTF and the other formats assimp reads;
// PLY files and Quake III levels occu reads itself).
#pragma once

#include <string>
#include <vector>

#include "scene/city.h"
#include "scene/quake3_bsp.h"
#include "scene/scene.h"

namespace occu {

// Loads every mesh of the file as triangles (polygons triangulated, normals
// generated where missing; node transforms applied). Throws
// std::runtime_error naming the file and assimp's reason when it cannot
// read it or it holds no triangles, and naming the file, mesh and vertex
// when a vertex coordinate is not finite (require_finite_vertices), and
// before assimp reads a file that would crash or hang it
// (scene/scene_file_guard.h). What it drops it says in a warning naming
// the file, the mesh and how many: meshes of points or lines, faces that
// are not triangles or index beyond their mesh, meshes left with no
// triangles; and normals that are zero or not finite, replaced by
// (0, 1, 0). Triangles whose corners are collinear to float precision
// have no surface and are left out without a word (collinear_corners,
// scene/scene.h; assimp's 2-cylinder engine holds 11,160 of zero area).
// Warnings go to `warnings` when given, standard error
// ("occu: warning: ...") otherwise.
//
// With `quake3.look` (the look a scene calls for, render/scene_renderer.h:
// Look::scene; the flag every program sets from its --look, for models as
// for levels), a mesh whose material names a diffuse picture (glTF: its
// base colour's) gets that picture (Mesh::image, Scene::images) and its
// texture coordinates (Mesh::texcoords), drawn times its material's diffuse
// colour (white where the material gives the picture alone). A picture is
// the file's embedded texture or a file beside the model (its path as a
// model made on Windows writes it, matched regardless of case where need
// be); it is decoded
// with stb_image once, and only when a mesh that is kept shows it. One that
// cannot be read leaves its meshes in their materials' colours, named in a
// warning. A model whose materials have no pictures (the IFC house) is the
// same in both looks: its materials' colours.
//
// Quake III levels (scene/quake3_bsp.h) occu reads itself: a path
// "ARCHIVE.pk3:maps/NAME.bsp" names a level inside a pk3 archive
// (scene/pk3_archive.h), and a file ending .bsp, or beginning "IBSP", is
// one; `quake3` says how finely their patches are tessellated.
Scene load_scene(const std::string &path, std::vector<std::string> *warnings = nullptr,
                 const Quake3Options &quake3 = {});

// The scene a program's --scene names: "city" (or empty) the procedural
// city of `city` (scene/city.h), "field" the flat field of small objects
// with its defaults (scene/field.h: no occlusion), anything else a file
// (load_scene, with `quake3` for a level; "./city" reads a file of that name).
Scene scene_by_name(const std::string &name, const CityOptions &city = {}, const Quake3Options &quake3 = {});
// Whether `name` is one of the generated scenes ("city", "field") rather than a file.
bool generated_scene_name(const std::string &name);

}  // namespace occu
