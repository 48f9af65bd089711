// SPDX-License-Identifier: MIT
// The colours scenes are drawn in: a palette of light facade hues (plaster,
// stone, brick, painted render) for the city's buildings and for the meshes
// of user scenes whose file gives no colour. Colours are albedos, RGB in
// [0, 1], before the renderer's lighting (render/shading.h).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace occu {

// The colours of one building.
struct BuildingColours {
    glm::vec3 wall;   // the facade
    glm::vec3 trim;   // ledges and cornices: lighter than a dark wall, darker than a light one
    glm::vec3 roof;
};

// How many facade hues the palette has.
std::uint32_t facade_hue_count();
// Hue `index` (taken modulo the count), varied by `variation` in [0, 1)
// (a little lighter or darker, a little warmer or cooler), with its trim and
// one of the roof colours, chosen by `roof` in [0, 1).
BuildingColours building_colours(std::uint32_t index, float variation, float roof);

// The street: asphalt, darker than the facades, so that their feet show.
glm::vec3 street_colour();

// Linear luminance (Rec. 709 weights) of an RGB colour.
float luminance(const glm::vec3 &rgb);

}  // namespace occu
