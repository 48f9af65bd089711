// SPDX-License-Identifier: MIT
#include "image/png.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <stdexcept>

using namespace occu;

TEST(Png, WritesBottomUpRowsTopFirstAndReadsThemBack)
{
    const int w = 3, h = 2;
    // Bottom row red, top row blue, as glReadPixels returns them.
    std::vector<std::uint8_t> rgba = {255, 0, 0, 255, 255, 0, 0, 255, 255, 0, 0, 255,
                                      0, 0, 255, 255, 0, 0, 255, 255, 0, 0, 255, 255};
    // Per process: meson runs this binary once per driver, at the same time.
    const std::string path = ::testing::TempDir() + "occu_png_test_" + std::to_string(getpid()) + ".png";
    write_png(path, w, h, rgba.data());
    int rw = 0, rh = 0;
    const auto back = read_png(path, rw, rh);
    std::remove(path.c_str());
    ASSERT_EQ(rw, w);
    ASSERT_EQ(rh, h);
    EXPECT_EQ(back[2], 255);          // first row read is the top: blue
    EXPECT_EQ(back[0], 0);
    EXPECT_EQ(back[w * 4 + 0], 255);  // second row: red
}

TEST(Png, ErrorsNameThePath)
{
    const std::uint8_t px[4] = {};
    try {
        write_png("/nonexistent-dir/x.png", 1, 1, px);
        FAIL() << "no exception";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.png"), std::string::npos);
    }
    int w, h;
    EXPECT_THROW(read_png("/nonexistent-dir/y.png", w, h), std::runtime_error);
}
