// SPDX-License-Identifier: MIT
// Text in images without fonts from anywhere: occu's own bitmap font, 5x7
// pixels a glyph (descenders 2 more) for the printable ASCII characters,
// drawn into RGBA8 images in client memory, for titles and legends of the
// images the demos write (render/top_view.h).
#pragma once

#include <cstdint>
#include <string_view>

namespace occu {

struct Rgba8 {
    std::uint8_t r, g, b, a;
};

// An RGBA8 image in client memory, top row first (as write_png writes it
// with bottom_up = false).
struct ImageRef {
    std::uint8_t *rgba;
    int width, height;
};

// The font's metrics at scale 1, in pixels: every glyph is `glyph_width`
// wide and advances the pen by `glyph_advance`; capitals and digits are
// `cap_height` tall, descenders reach `glyph_height`; lines of text are
// `line_height` apart.
constexpr int glyph_width = 5, glyph_advance = 6, cap_height = 7, glyph_height = 9, line_height = 11;

// Width in pixels of `text` drawn at `scale` (every font pixel a scale x
// scale square): from the left edge of the first glyph to the right edge
// of the last, with no spacing after it; 0 for the empty string.
int text_width(std::string_view text, int scale = 1);

// Draws `text` on one line with the top-left corner of its first glyph at
// (x, y), y counted downwards from the top row, at `scale`. Pixels outside
// the image are left out. A character the font lacks (outside printable
// ASCII) is drawn as '?'. Returns the x just right of the last glyph.
int draw_text(ImageRef image, int x, int y, std::string_view text, Rgba8 colour, int scale = 1);

// Fills the rectangle of `width` x `height` pixels with top-left corner
// (x, y), clipped to the image.
void fill_rect(ImageRef image, int x, int y, int width, int height, Rgba8 colour);

// Whether the glyph of `c` has ink at (column, row), 0 <= column <
// glyph_width, 0 <= row < glyph_height; what draw_text draws.
bool glyph_ink(char c, int column, int row);

}  // namespace occu
