// GL_MESAX_occlusion_unit's token values collide with nothing the Khronos
// registry assigns (spec, issue 16): they lie in Mesa's block 0x9790-0x979F
// and are none of the values gl.xml (2026-05-20) assigns in Mesa's blocks.
#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "gl/gl_headers.h"
#include "GL/mesax_occlusion_unit.h"

namespace {

// Values gl.xml assigns in Mesa's blocks 0x8750-0x875F, 0x8BB0-0x8BBF,
// 0x9740-0x975F and 0x9790-0x979F (fact from the registry, by value).
const std::vector<std::pair<std::uint32_t, const char *>> registered = {
    {0x8750, "GL_DEPTH_STENCIL_MESA"},           {0x875F, "GL_PROGRAM_BINARY_FORMAT_MESA"},
    {0x8BB8, "GL_TILE_RASTER_ORDER_FIXED_MESA"}, {0x8BBB, "GL_FRAMEBUFFER_FLIP_Y_MESA"},
    {0x8BBC, "GL_FRAMEBUFFER_FLIP_X_MESA"},      {0x8BBD, "GL_FRAMEBUFFER_SWAP_XY_MESA"},
    {0x8BBE, "GL_CONST_BW_TILING_MESA"},         {0x9790, "GL_BUFFER_CLIENT_POINTER_SIZE_MESA"},
};

bool assigned(std::uint32_t v)
{
    if ((v >= 0x8750 && v <= 0x875F) || (v >= 0x8BB0 && v <= 0x8BBE) || (v >= 0x9740 && v <= 0x975A))
        return true;   // every value of these ranges is assigned
    for (const auto &r : registered)
        if (r.first == v)
            return true;
    return false;
}

}  // namespace

TEST(Tokens, InMesasBlockAndAssignedToNothingElse)
{
    const std::uint32_t tokens[] = {GL_BRIEF_OCCLUSION_MESAX,          GL_VERBOSE_OCCLUSION_MESAX,
                                    GL_MAX_OCCLUSION_TILES_MESAX,      GL_OCCLUSION_TILE_COUNT_MESAX,
                                    GL_OCCLUSION_TILE_MESAX,           GL_OCCLUSION_BUFFER_COUNT_MESAX,
                                    GL_OCCLUSION_BUFFER_SIZE_MESAX,    GL_OCCLUSION_BUFFER_POINTER_MESAX};
    const std::size_t n = sizeof(tokens) / sizeof(tokens[0]);
    for (std::uint32_t t : tokens) {
        EXPECT_FALSE(assigned(t)) << std::hex << "0x" << t << " is assigned in the registry";
        EXPECT_TRUE(t >= 0x9790 && t <= 0x979F) << std::hex << "0x" << t << " is outside Mesa's block 0x9790-0x979F";
    }
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            EXPECT_NE(tokens[i], tokens[j]);
}
