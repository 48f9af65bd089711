// SPDX-License-Identifier: MIT
#include "camera/footprint.h"

#include <cmath>

namespace occu {

namespace {

// Whether the CPU has AVX2, set before main (with no guard to test on each
// call); a call during another file's static initialization, before this
// is set, takes the scalar kernel, whose answer is the same.
const bool cpu_has_avx2 = (__builtin_cpu_init(), __builtin_cpu_supports("avx2"));

}  // namespace

std::optional<Footprint> box_footprint(const glm::mat4 &view_projection, const glm::vec3 &eye, const Aabb &box,
                                       int viewport_width, int viewport_height)
{
    return cpu_has_avx2 ? box_footprint_avx2(view_projection, eye, box, viewport_width, viewport_height)
                : box_footprint_scalar(view_projection, eye, box, viewport_width, viewport_height);
}

std::optional<Footprint> box_footprint_scalar(const glm::mat4 &view_projection, const glm::vec3 &eye, const Aabb &box,
                                              int viewport_width, int viewport_height)
{
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(box.min[a]) || !std::isfinite(box.max[a]))
            return std::nullopt;
    const auto p = project_box(view_projection, eye, box);
    // A non-finite box or projection (a degenerate camera): no
    // footprint, so the box is taken as visible rather than tested.
    if (!p || !std::isfinite(p->ndc_min.x) || !std::isfinite(p->ndc_min.y) || !std::isfinite(p->ndc_max.x) ||
        !std::isfinite(p->ndc_max.y) || !std::isfinite(p->window_z_near))
        return std::nullopt;
    // NDC to window x, y; floor and ceil take in every pixel whose centre
    // the projection reaches, and one more pixel each side absorbs rounding.
    // Clamped in float first, so that far-off projections cannot overflow int.
    auto to_window = [](float ndc, int size) {
        const float w = (ndc + 1.0f) * 0.5f * float(size);
        return std::clamp(w, -2.0f, float(size) + 2.0f);
    };
    const PixelRect grown{int(std::floor(to_window(p->ndc_min.x, viewport_width))) - 1,
                          int(std::floor(to_window(p->ndc_min.y, viewport_height))) - 1,
                          int(std::ceil(to_window(p->ndc_max.x, viewport_width))) + 1,
                          int(std::ceil(to_window(p->ndc_max.y, viewport_height))) + 1};
    return Footprint{grown.clamped({0, 0, viewport_width, viewport_height}), p->window_z_near};
}

}  // namespace occu
