// SPDX-License-Identifier: MIT
// Cameras and view frusta. OpenGL conventions: the camera looks down its
// -z axis, clip space z in [-w, w], window depth in [0, 1].
#pragma once

#include <array>
#include <optional>

#include <glm/glm.hpp>

#include "geometry/aabb.h"

namespace occu {

struct Camera {
    glm::vec3 position{0.0f, 1.7f, 0.0f};
    glm::vec3 target{0.0f, 1.7f, -1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};   // where parallel to the view direction, view() picks a world axis
    float fovy_degrees = 60.0f;
    float aspect = 1.0f;
    float near_plane = 0.5f;
    float far_plane = 5000.0f;

    glm::mat4 view() const;
    glm::mat4 projection() const;
    glm::mat4 view_projection() const { return projection() * view(); }
};

// The six planes of a view-projection matrix, normals pointing inwards
// (Gribb and Hartmann's extraction from the matrix rows).
// A box's footprint on screen: normalized device x and y bounds and the
// nearest window depth of its corners. Empty when the box holds the eye or
// reaches in front of the near plane, where its projection is not its
// footprint (occlusion tests then take the box as visible).
struct BoxProjection {
    glm::vec2 ndc_min, ndc_max;
    float window_z_near;
};
std::optional<BoxProjection> project_box(const glm::mat4 &view_projection, const glm::vec3 &eye, const Aabb &box);

class Frustum {
public:
    enum class Side { outside, intersecting, inside };

    explicit Frustum(const glm::mat4 &view_projection);

    // Conservative: `outside` only when one plane has the whole box behind it.
    Side classify(const Aabb &box) const;
    // The same answer for a box inside one classified before (a child's box
    // inside its parent's), testing only the planes in `crossing` (bit i:
    // planes()[i]), those the enclosing box reaches across: a box has the
    // others wholly in front of it as its enclosing box does. On return
    // `crossing` holds the planes this box reaches across, for the boxes
    // inside it. All six: classify(box).
    static constexpr unsigned all_planes = 0x3Fu;
    Side classify(const Aabb &box, unsigned &crossing) const;

    const std::array<glm::vec4, 6> &planes() const { return planes_; }

private:
    std::array<glm::vec4, 6> planes_;
    // The same planes coordinate by coordinate, for four planes a step in
    // SIMD lanes (the last two lanes zero: never behind).
    alignas(16) float lane_x_[8] = {}, lane_y_[8] = {}, lane_z_[8] = {}, lane_w_[8] = {};
};

}  // namespace occu
