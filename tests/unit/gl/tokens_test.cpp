// SPDX-License-Identifier: MIT
// The token values of GL_MESAX_occlusion_unit and GL_MESAX_occlusion_unit_async
// collide with nothing the Khronos registry assigns or will assign soon (spec
// MESAX_occlusion_unit, issue 16): every value lies in no vendor's block of
// gl.xml, in the range it reserves for blocks yet to be handed out, far from
// where the next one starts, and is no value gl.xml assigns; all of them fit
// one block of 16, the block the extensions would request, and 16 bits, the
// width in which Mesa keeps some enums (GLenum16, e.g. the render mode).
// The registry's facts are gl_registry_blocks.inc, made from gl.xml by
// registry_blocks.py.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "gl/gl_headers.h"
#include "GL/mesax_occlusion_unit.h"

namespace {

struct RegistryBlock {
    std::uint32_t start, end;
    const char *vendor;
    bool reserved;   // held by no vendor: kept for blocks yet to be handed out
};

struct RegistryValue {
    std::uint32_t value;
    const char *name;
};

#include "gl_registry_blocks.inc"

struct Token {
    std::uint32_t value;
    const char *name;
};

#define OU_TOKEN(name) Token{name, #name}
const std::vector<Token> tokens = {
    OU_TOKEN(GL_BRIEF_OCCLUSION_MESAX),
    OU_TOKEN(GL_VERBOSE_OCCLUSION_MESAX),
    OU_TOKEN(GL_MAX_OCCLUSION_TILES_MESAX),
    OU_TOKEN(GL_OCCLUSION_TILE_COUNT_MESAX),
    OU_TOKEN(GL_OCCLUSION_TILE_MESAX),
    OU_TOKEN(GL_OCCLUSION_BUFFER_COUNT_MESAX),
    OU_TOKEN(GL_OCCLUSION_BUFFER_SIZE_MESAX),
    OU_TOKEN(GL_OCCLUSION_BUFFER_POINTER_MESAX),
    OU_TOKEN(GL_OCCLUSION_PASS_RESULT_MESAX),
    OU_TOKEN(GL_OCCLUSION_PASS_RESULT_AVAILABLE_MESAX),
    OU_TOKEN(GL_OCCLUSION_PASS_RESULT_NO_WAIT_MESAX),
    OU_TOKEN(GL_CURRENT_OCCLUSION_PASS_MESAX),
    OU_TOKEN(GL_CONSERVATIVE_OCCLUSION_MESAX),
};
#undef OU_TOKEN

// The registry hands out blocks of 16 from the start of its reservation up;
// the tokens keep this many blocks of room from that start.
constexpr std::uint32_t free_blocks_before_tokens = 256;

std::string hex(std::uint32_t v)
{
    char text[16];
    std::snprintf(text, sizeof(text), "0x%X", v);
    return text;
}

}  // namespace

TEST(Tokens, RegistryTableIsWhole)
{
    // The blocks tile the enumerant space from 0 without gaps or overlaps,
    // so "the block holding a value" is well defined.
    ASSERT_GT(sizeof(registry_blocks) / sizeof(registry_blocks[0]), 100u);
    EXPECT_EQ(registry_blocks[0].start, 0u);
    for (std::size_t i = 1; i < sizeof(registry_blocks) / sizeof(registry_blocks[0]); ++i)
        EXPECT_EQ(registry_blocks[i].start, registry_blocks[i - 1].end + 1)
            << "after the block ending at " << hex(registry_blocks[i - 1].end);
}

TEST(Tokens, InNoVendorsBlockFarFromTheNextOne)
{
    for (const Token &t : tokens) {
        const RegistryBlock *holder = nullptr;
        for (const RegistryBlock &b : registry_blocks)
            if (b.start <= t.value && t.value <= b.end)
                holder = &b;
        ASSERT_NE(holder, nullptr) << t.name << " " << hex(t.value) << " is outside every block of gl.xml";
        EXPECT_TRUE(holder->reserved) << t.name << " " << hex(t.value) << " lies in " << holder->vendor
                                      << "'s block " << hex(holder->start) << "-" << hex(holder->end);
        if (holder->reserved) {
            EXPECT_GE(t.value, holder->start + 16 * free_blocks_before_tokens)
                << t.name << " " << hex(t.value) << " is among the next blocks the registry hands out from "
                << hex(holder->start);
        }
    }
}

TEST(Tokens, NoValueTheRegistryAssigns)
{
    for (const Token &t : tokens)
        for (const RegistryValue &v : registry_values_in_reservations)
            EXPECT_NE(t.value, v.value) << t.name << " is " << v.name << " in gl.xml";
}

TEST(Tokens, DistinctInOneBlockOf16And16Bits)
{
    for (std::size_t i = 0; i < tokens.size(); ++i) {
        EXPECT_LE(tokens[i].value, 0xFFFFu) << tokens[i].name << " does not fit a GLenum16";
        EXPECT_EQ(tokens[i].value & ~0xFu, tokens[0].value & ~0xFu)
            << tokens[i].name << " " << hex(tokens[i].value) << " is outside the block of " << tokens[0].name;
        for (std::size_t j = i + 1; j < tokens.size(); ++j)
            EXPECT_NE(tokens[i].value, tokens[j].value) << tokens[i].name << " and " << tokens[j].name;
    }
}
