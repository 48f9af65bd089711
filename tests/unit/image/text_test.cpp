// SPDX-License-Identifier: MIT
#include "image/text.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

using namespace occu;

namespace {

// An image with guard bytes before and after it, to catch writes outside it.
struct Canvas {
    static constexpr std::size_t guard = 4096;
    int width, height;
    std::vector<std::uint8_t> memory;
    Canvas(int w, int h) : width(w), height(h), memory(std::size_t(w) * std::size_t(h) * 4 + 2 * guard, 0) {}
    std::uint8_t *pixels() { return memory.data() + guard; }
    ImageRef ref() { return {pixels(), width, height}; }
    bool ink(int x, int y) const
    {
        return memory[guard + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4 + 3] != 0;
    }
    bool guards_intact() const
    {
        for (std::size_t i = 0; i < guard; ++i)
            if (memory[i] || memory[memory.size() - 1 - i])
                return false;
        return true;
    }
};

// The smallest rectangle holding every pixel with ink: x0, y0, x1, y1 (exclusive), or all 0.
std::vector<int> ink_box(const Canvas &c)
{
    int x0 = c.width, y0 = c.height, x1 = 0, y1 = 0;
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x)
            if (c.ink(x, y)) {
                x0 = std::min(x0, x);
                y0 = std::min(y0, y);
                x1 = std::max(x1, x + 1);
                y1 = std::max(y1, y + 1);
            }
    return x1 ? std::vector<int>{x0, y0, x1, y1} : std::vector<int>{0, 0, 0, 0};
}

const Rgba8 black{0, 0, 0, 255};

}  // namespace

TEST(Text, WidthIsAdvanceTimesCharactersLessTheLastGap)
{
    EXPECT_EQ(text_width(""), 0);
    EXPECT_EQ(text_width("a"), glyph_width);
    EXPECT_EQ(text_width("frame 20"), 8 * glyph_advance - 1);
    EXPECT_EQ(text_width("frame 20", 3), 3 * (8 * glyph_advance - 1));
}

TEST(Text, DrawnStringHasInkExactlyAsWideAsItsWidth)
{
    // 'H' has ink in its first and last columns, so the ink spans the whole width.
    for (int scale : {1, 2, 3}) {
        Canvas c(260, 60);
        const std::string s = "H 12.5 ms H";
        const int end = draw_text(c.ref(), 7, 5, s, black, scale);
        EXPECT_EQ(end, 7 + text_width(s, scale));
        const std::vector<int> box = ink_box(c);
        EXPECT_EQ(box[0], 7) << "scale " << scale;
        EXPECT_EQ(box[1], 5) << "scale " << scale;
        EXPECT_EQ(box[2] - box[0], text_width(s, scale)) << "scale " << scale;
        EXPECT_EQ(box[3] - box[1], cap_height * scale) << "scale " << scale;   // no descender in s
    }
}

TEST(Text, DescendersReachBelowTheBaseline)
{
    Canvas c(40, 20);
    draw_text(c.ref(), 0, 0, "gy", black);
    EXPECT_EQ(ink_box(c)[3], glyph_height);
}

TEST(Text, EveryPrintableCharacterHasItsOwnGlyph)
{
    std::set<std::vector<bool>> seen;
    for (char ch = ' '; ch <= '~'; ++ch) {
        std::vector<bool> bits;
        int ink = 0;
        for (int r = 0; r < glyph_height; ++r)
            for (int col = 0; col < glyph_width; ++col) {
                bits.push_back(glyph_ink(ch, col, r));
                ink += bits.back();
            }
        if (ch == ' ')
            EXPECT_EQ(ink, 0);
        else
            EXPECT_GT(ink, 0) << "'" << ch << "' has no ink";
        EXPECT_TRUE(seen.insert(bits).second) << "'" << ch << "' looks like another character";
    }
}

TEST(Text, UnknownCharactersAreQuestionMarks)
{
    for (int r = 0; r < glyph_height; ++r)
        for (int col = 0; col < glyph_width; ++col)
            EXPECT_EQ(glyph_ink('\x01', col, r), glyph_ink('?', col, r));
}

TEST(Text, ClipsAtTheImageEdges)
{
    Canvas c(10, 6);
    // Partly left of, above, right of and below the image: no write outside it.
    draw_text(c.ref(), -3, -4, "WWWW", black, 2);
    draw_text(c.ref(), 6, 3, "WWWW", black, 2);
    EXPECT_NE(ink_box(c)[2], 0);
    EXPECT_TRUE(c.guards_intact());
    fill_rect(c.ref(), -5, -5, 100, 100, black);
    EXPECT_TRUE(c.guards_intact());
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x)
            EXPECT_TRUE(c.ink(x, y));
}
