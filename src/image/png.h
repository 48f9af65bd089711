// SPDX-License-Identifier: MIT
// PNG output for frames and top views.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace occu {

// Writes an RGBA8 image. `bottom_up`: row 0 of `rgba` is the bottom row, as
// OpenGL returns it. Throws std::runtime_error naming the path on failure.
void write_png(const std::string &path, int width, int height, const std::uint8_t *rgba, bool bottom_up = true);

// Reads an 8-bit RGBA PNG (top row first); throws std::runtime_error naming
// the path when it cannot. For tests and comparisons.
std::vector<std::uint8_t> read_png(const std::string &path, int &width, int &height);

}  // namespace occu
