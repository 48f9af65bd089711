// SPDX-License-Identifier: MIT
// Pre-lit vertex colours: the lighting of every frame, computed once on the
// CPU when the renderer builds its vertex buffers (render/scene_renderer.h),
// so that frames need no lighting state and cost what unlit frames cost.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace occu {

// The colour a surface of colour `albedo` (RGB in [0, 1]) with unit normal
// `normal` is drawn in: lit from above and from the +x and +z sides, so
// that the four wall orientations, roofs and the street, and the undersides
// of ledges each get a brightness of their own (render/shading.cpp). At most
// 0.97 times the albedo (no channel clamps, so different albedos stay
// different colours); at least 0.3 times it.
glm::vec3 prelit_colour(const glm::vec3 &albedo, const glm::vec3 &normal);

// The same as RGBA8 (alpha 255); a non-finite albedo or normal gives grey.
void prelit_rgba8(const glm::vec3 &albedo, const glm::vec3 &normal, std::uint8_t rgba[4]);

// `colour` itself as RGBA8 (alpha 255), for surfaces that give their own
// light (Mesh::shaded false); a non-finite colour gives grey.
void unlit_rgba8(const glm::vec3 &colour, std::uint8_t rgba[4]);

}  // namespace occu
