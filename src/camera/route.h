// SPDX-License-Identifier: MIT
// Camera routes through a scene, like the papers' walkthrough paths
// (Poon and Wang, section 6: best, average and worst routes).
//
// Built-in routes for the default city (see scene/city.h):
//   dense   the paper's best case: street level from the lower left corner,
//           looking diagonally across the blocks towards the centre: the
//           nearest buildings hide almost all of the city in the frustum;
//   street  street level along the middle street, looking down it: a long
//           sight line between facades;
//   medium  the same walk, looking 35 degrees aside, into crossings and
//           courtyards;
//   open    150 m up outside the city, looking across its roofs: little
//           is hidden (the paper's worst case).
// Routes for any scene:
//   orbit          around the scene's bounding sphere, looking at its centre;
//   overhead       from above, looking down at 60 degrees, across the scene
//                  (the route of the field, scene/field.h: from there
//                  nothing of the field hides anything);
//   random:N:SEED  N cameras at random points inside the scene's bounds,
//                  looking in random directions (N frames, whatever `frames` is);
//                  in a Quake III level, only points in its open space: a
//                  BSP leaf of a cluster (>= 0), not one inside a solid;
//                  in a model read from a file (a building), only points
//                  inside it: rays in 14 directions from the eye all hit
//                  the model (spatial/inside_points.h), so eyes lie in its
//                  rooms, never outside it.
// Routes for levels (scene/level.h; Quake III levels, scene/quake3_bsp.h):
//   spawn, spawn:K  every player spawn point of the level in turn, from the
//                  eye of a player standing there, looking along its angle
//                  and then turning through 360 degrees about the vertical,
//                  K views a spawn point (8, every 45 degrees, by default),
//                  level, with Quake III's 90 degree horizontal field of view
//                  (K x spawn points frames, whatever `frames` is).
// A route file has one camera per line, "px py pz tx ty tz" (position and
// target); '#' starts a comment.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "scene/city.h"

namespace occu {

struct Level;

// Whether a random eye may stand at a point (route random:N:SEED in a
// model: inside_model of spatial/inside_points.h); empty: anywhere.
using EyeTest = std::function<bool(const glm::vec3 &)>;

// The lens of the street-level routes (dense, street, medium), which
// occluder preprocessing places its views with: 60 degrees, near plane
// 0.5 m, far plane twice the scene's diagonal.
Camera street_level_lens(const Aabb &bounds, float aspect);

// `name`: dense, street, medium, open, orbit, overhead, random:N:SEED,
// spawn[:K], or a route file's path. `level`: the scene's Quake III level
// (Scene::quake3), or null. `eye_inside`: where random eyes may stand
// besides a level's open leaves (a model's inside), or empty. Throws
// std::invalid_argument (unknown name; spawn without a level or a level
// without spawn points; random eyes that find no open leaf, or no point
// `eye_inside` keeps, after a bounded number of candidates) or std::runtime_error (a file it cannot read or
// parse, naming the file and line; a number that is not a finite float,
// or a camera whose view direction is not, is refused).
std::vector<Camera> make_route(const std::string &name, const Aabb &scene_bounds, const CityOptions &city,
                               int frames, float aspect, const Level *level = nullptr,
                               const EyeTest &eye_inside = {});

// Whether the cameras of route `name` are unrelated views (random:N:SEED):
// what one frame saw says nothing of the next, so the traversal's policies
// across frames (traversal/policies.h: temporal coherence, the switch-off)
// have nothing to go on, and the benches run such routes without them.
bool unrelated_views(const std::string &name);

// The cameras of the route random:COUNT:SEED (eyes uniformly inside the
// bounds, buildings and streets alike; random headings; pitch within 60
// degrees of the horizon), each with a vertical field of view drawn
// uniformly from [fov_min, fov_max] degrees by a generator of its own, so
// that eyes and directions are the route's. Throws as make_route does, and
// std::invalid_argument for a field of view outside [1, 170] or fov_min > fov_max.
std::vector<Camera> random_views(const Aabb &scene_bounds, long count, unsigned long seed, float aspect, float fov_min,
                                 float fov_max, const Level *level = nullptr, const EyeTest &eye_inside = {});

}  // namespace occu
