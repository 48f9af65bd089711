// SPDX-License-Identifier: MIT
#include "render/shading.h"

#include <algorithm>
#include <cmath>

namespace occu {

namespace {

// The light, linear in the normal (a wrapped sky light rather than a sun's
// Lambert term, so that no face orientation goes black): brightness 0.74 +
// dot(normal, light). Walls facing +x get 0.87, +z 0.79, -z 0.69, -x 0.61;
// roofs and the street 0.96; undersides 0.52.
const glm::vec3 light{0.13f, 0.22f, 0.05f};
constexpr float ambient = 0.74f;

bool finite(const glm::vec3 &v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

glm::vec3 prelit_colour(const glm::vec3 &albedo, const glm::vec3 &normal)
{
    const float brightness = std::clamp(ambient + glm::dot(normal, light), 0.3f, 0.97f);
    return glm::clamp(albedo, 0.0f, 1.0f) * brightness;
}

void prelit_rgba8(const glm::vec3 &albedo, const glm::vec3 &normal, std::uint8_t rgba[4])
{
    const glm::vec3 c = finite(albedo) && finite(normal) ? prelit_colour(albedo, normal) : glm::vec3(0.5f);
    for (int k = 0; k < 3; ++k)
        rgba[k] = std::uint8_t(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
    rgba[3] = 255;
}

void unlit_rgba8(const glm::vec3 &colour, std::uint8_t rgba[4])
{
    const glm::vec3 c = finite(colour) ? colour : glm::vec3(0.5f);
    for (int k = 0; k < 3; ++k)
        rgba[k] = std::uint8_t(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
    rgba[3] = 255;
}

}  // namespace occu
