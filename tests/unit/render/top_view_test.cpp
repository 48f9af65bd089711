// SPDX-License-Identifier: MIT
#include "render/top_view.h"

#include <gtest/gtest.h>

#include <vector>

using namespace occu;

namespace {
// Rows of a white image with dark pixels (text), top row first.
std::vector<int> dark_rows(const std::vector<std::uint8_t> &rgba, int width, int height)
{
    std::vector<int> rows;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            if (rgba[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4] < 100) {
                rows.push_back(y);
                break;
            }
    return rows;
}
}  // namespace

TEST(TopView, MapIsASquareBetweenTitleAndLegend)
{
    for (int size : {128, 256, 512, 1024}) {
        const PixelRect map = top_view_map_area(size, size);
        EXPECT_EQ(map.width(), map.height()) << size;
        EXPECT_GT(map.width(), size / 2) << size;
        EXPECT_GE(map.x0, 0);
        EXPECT_LE(map.x1, size);
        EXPECT_GT(map.y0, 0) << "no room for the legend below";
        EXPECT_LT(map.y1, size) << "no room for the title above";
    }
}

TEST(TopView, CaptionWritesTitleAboveAndLegendBelowTheMapOnly)
{
    const int size = 512;
    std::vector<std::uint8_t> image(std::size_t(size) * size * 4, 255);
    TopViewCaption caption;
    caption.strategy = "om-ps";
    caption.frame = 20;
    caption.ms = 3.37;
    caption.culled_percent = 97.9;
    caption.efficiency_percent = 97.8;
    caption.wrongly_culled = 0;
    caption_top_view({image.data(), size, size}, caption);
    const PixelRect map = top_view_map_area(size, size);
    const int map_top = size - map.y1, map_bottom = size - map.y0;   // rows from the top
    const std::vector<int> rows = dark_rows(image, size, size);
    ASSERT_FALSE(rows.empty());
    int above = 0, below = 0;
    for (int y : rows) {
        EXPECT_TRUE(y < map_top || y >= map_bottom) << "text over the map at row " << y;
        above += y < map_top;
        below += y >= map_bottom;
    }
    EXPECT_GT(above, 2 * cap_height) << "no title of two lines";
    EXPECT_GT(below, 2 * cap_height) << "no legend";
    // The swatches of the legend are in the map's colours.
    int green = 0;
    const Rgba8 g = top_view_colours::drawn.rgba8();
    for (std::size_t i = 0; i < image.size(); i += 4)
        green += image[i] == g.r && image[i + 1] == g.g && image[i + 2] == g.b;
    EXPECT_GT(green, 0);
}
