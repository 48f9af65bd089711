// SPDX-License-Identifier: MIT
// Whether a point lies inside a model: in a room of a building, the cabin
// of a ship, anywhere a camera sees the model around it rather than its
// outside or the backs of its walls. A model read from a file says nothing
// about its rooms (it need not even be closed), so the test is a vote of
// rays: the point is inside when a ray in each of `inside_ray_directions`
// directions from it hits one of the model's triangles. A point outside
// an open or closed shape has some direction with nothing in it; a point in
// a room with windows may be refused through a window, which only makes
// the test stricter. Rays are pruned by the hierarchy's node boxes (the
// boxes bound their subtrees' triangles, spatial/hierarchy.h).
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "spatial/hierarchy.h"

namespace occu {

// The six axis directions and the eight diagonals of a cube: no direction
// is more than 35.3 degrees from one of them, so an opening wider than
// that, in any direction, refuses the point.
inline constexpr int inside_ray_directions = 14;

// The ray directions, unit length, in a fixed order (axes first).
const glm::vec3 &inside_ray_direction(int i);

// Whether the ray from `origin` along `direction` hits one of `scene`'s
// triangles (hierarchy built over `scene`) at a distance above zero;
// either face counts.
bool ray_hits_model(const Scene &scene, const Hierarchy &hierarchy, const glm::vec3 &origin,
                    const glm::vec3 &direction);

// Whether every one of the inside_ray_directions rays from `point` hits
// the model; false as soon as one misses.
bool inside_model(const Scene &scene, const Hierarchy &hierarchy, const glm::vec3 &point);

}  // namespace occu
