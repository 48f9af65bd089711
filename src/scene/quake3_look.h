// SPDX-License-Identifier: MIT
// The pictures of a Quake III level's look (Quake3Options::look): each
// mesh's texture, found as the game finds it (its renderer's R_FindShader
// and R_FindImageFile): a shader of the mesh's name in a script
// (scripts/*.shader) gives the picture of its first stage that draws one
// (`map`, `clampmap`, or the first frame of `animmap`; not `$lightmap` nor
// `$whiteimage`), otherwise the name itself is the picture's; either is
// tried with the extension .tga, then .jpg. Files come from every pk3 of
// the level's own directory, a later one (by name) replacing an earlier
// one's file of the same name, as the game's search path does. Pictures
// are decoded with stb_image (Debian's libstb), only those a mesh uses,
// each once.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace occu {

// Sets Mesh::image of the meshes of `scene` (read with the look) whose
// texture is found in the pk3 files beside `archive`, appending the decoded
// pictures to scene.images. A sky (Mesh::shaded false) keeps its colour.
// A texture found nowhere, or a picture that does not decode, leaves its
// mesh without one (drawn in its light alone) and is counted in a warning
// naming up to five; an archive directory that cannot be listed, or a pk3
// that cannot be opened, throws std::runtime_error naming it.
void read_level_pictures(Scene &scene, const std::string &archive, std::vector<std::string> &warnings);

}  // namespace occu
