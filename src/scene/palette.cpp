// SPDX-License-Identifier: MIT
#include "scene/palette.h"

#include <algorithm>
#include <array>

namespace occu {

namespace {

// Light facade hues, far enough apart that neighbouring buildings differ at a glance.
const std::array<glm::vec3, 10> facades = {{
    {0.94f, 0.88f, 0.74f},   // cream plaster
    {0.91f, 0.74f, 0.45f},   // ochre
    {0.86f, 0.53f, 0.39f},   // terracotta
    {0.76f, 0.42f, 0.34f},   // brick
    {0.94f, 0.69f, 0.63f},   // salmon
    {0.67f, 0.77f, 0.88f},   // powder blue
    {0.67f, 0.79f, 0.58f},   // sage
    {0.83f, 0.82f, 0.78f},   // limestone
    {0.53f, 0.77f, 0.74f},   // teal
    {0.78f, 0.71f, 0.87f},   // lavender
}};

const std::array<glm::vec3, 4> roofs = {{
    {0.40f, 0.43f, 0.49f},   // slate
    {0.67f, 0.33f, 0.25f},   // clay tiles
    {0.40f, 0.58f, 0.52f},   // weathered copper
    {0.60f, 0.59f, 0.56f},   // gravel
}};

}  // namespace

std::uint32_t facade_hue_count()
{
    return std::uint32_t(facades.size());
}

float luminance(const glm::vec3 &c)
{
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

BuildingColours building_colours(std::uint32_t index, float variation, float roof)
{
    variation = std::clamp(variation, 0.0f, 1.0f);
    const glm::vec3 base = facades[index % facades.size()];
    // Lighter or darker by up to 8%, warmer or cooler by up to 3%.
    const float light = 0.92f + 0.14f * variation, warm = 0.06f * (variation - 0.5f);
    const glm::vec3 wall = glm::clamp(base * light + glm::vec3(warm, 0.0f, -warm), 0.0f, 1.0f);
    // Ledges stand out from the wall: a darker band on a light facade, a
    // near-white one on a dark facade.
    const glm::vec3 trim = luminance(wall) > 0.72f ? wall * 0.62f : glm::mix(wall, glm::vec3(0.97f, 0.96f, 0.93f), 0.75f);
    const auto r = std::min<std::size_t>(roofs.size() - 1, std::size_t(std::clamp(roof, 0.0f, 1.0f) * roofs.size()));
    return {wall, trim, roofs[r]};
}

glm::vec3 street_colour()
{
    return {0.43f, 0.43f, 0.45f};
}

}  // namespace occu
