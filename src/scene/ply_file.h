// SPDX-License-Identifier: MIT
// PLY (Turk's polygon file format: a header of elements and their typed
// properties, then their values in ASCII or binary) read by occu itself.
//
// assimp 5.2.5's PLY importer writes past its buffers on malformed files
// that every check from outside let through: the scene-file fuzzer saw
// AddressSanitizer's heap metadata overwritten with vertex floats and a
// property name in 4 of 10 runs of 100,000 inputs (docs/fuzzing.md).
// A PLY file is a header and a table of numbers, so occu reads it here,
// every read bounded, and assimp never sees it.
//
// What is read: the "vertex" element's x, y and z (and red, green and blue
// where it has them, 0-255 for integer types, 0-1 for floating ones), the
// "face" element's vertex_indices (or vertex_index) lists as polygons,
// fan-triangulated; other elements and properties are read past. Refused,
// with a message naming the file: a header outside PLY's grammar (the
// first line 'ply', a format line, then comment, obj_info, element and
// property lines of PLY's types, until end_header; a line of another
// first word is read as a comment, with a warning, as old exporters wrote
// comments without 'comment'), element counts
// beyond what the data could hold, data that ends early or a value that
// is not a number (ASCII files: one line per element instance, as every
// writer puts them), a vertex coordinate that is not finite, faces of no
// indices or indexing beyond the vertices. Faces of one or two vertices
// are dropped with a warning naming the file and the count.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace occu {

// The file's one mesh, smooth normals computed, bounds updated. Throws
// std::runtime_error naming `path`; warnings go to `warnings`.
Mesh read_ply(const std::string &path, const std::vector<char> &bytes, std::vector<std::string> &warnings);

}  // namespace occu
