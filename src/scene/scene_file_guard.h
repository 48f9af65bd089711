// SPDX-License-Identifier: MIT
// Checks of a scene file before assimp reads it: what Debian's assimp
// 5.2.5 would crash on, overflow a buffer with or hang on, found by the
// scene-file fuzzer (tests/fuzz/scene_file_fuzz.cpp). load_scene runs it
// first; assimp runs in occu's process, so its crash would be occu's.
//
// glTF (.gltf JSON, .glb binary): the JSON is parsed (strictly, as
// rapidjson does by default, nesting at most 64 deep) and every buffer,
// buffer view and accessor checked to lie inside the data it names
// (assimp checks an accessor's count against its view's length but not
// its offsets: a heap overflow); a triangle strip or fan needs 3 vertices
// and a line strip or loop 2 (assimp allocates count - 2 faces: 2^64 for
// fewer); data URIs must have a short header (assimp keeps offsets into
// it in a char) and no control characters. Only glTF 2 is read (assimp's
// glTF 1 importer is older and unchecked here); sparse accessors and
// accessors without a buffer view are refused (occu's scenes are static
// meshes; assimp 5.2.5 writes sparse values at indices it does not check).
//
// PLY files assimp never reads: occu reads them itself (scene/ply_file.h),
// since assimp's PLY importer wrote past its buffers on malformed files
// that no check from outside could tell from good ones.
//
// Which checks run: by the extension (.gltf, .glb), and for other
// extensions by the content, as assimp picks its importer.
#pragma once

#include <string>
#include <vector>

namespace occu {

// Throws std::runtime_error naming `path` and what is wrong; returns when
// assimp may read the file (it may still refuse it). `bytes`: the file's.
void guard_scene_file(const std::string &path, const std::vector<char> &bytes);

// Whether assimp would read the file with its PLY importer: the extension
// .ply, or an extension no importer claims and "ply" in its first 200
// bytes. load_scene reads such files with read_ply instead.
bool assimp_would_read_as_ply(const std::string &path, const std::vector<char> &bytes);

}  // namespace occu
