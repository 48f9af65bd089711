// SPDX-License-Identifier: MIT
// Occluder shrinking for 2.5D occluders of constant height: Wonka, Wimmer
// and Schmalstieg, "Visibility Preprocessing with Occluder Fusion for Urban
// Walkthroughs" (2000), sections 2.1 ("Occluder fusion by occluder
// shrinking and point sampling", figures 5 to 7) and 4.4 ("Occluders with
// constant height", figure 8).
//
// "An object classified as occluded by the shrunk occluder will remain
// occluded with respect to the original larger occluder when moving the
// viewpoint no more than epsilon from its original position": a point of
// the shrunk footprint lies at least epsilon from every point outside the
// original one (its erosion by a disc of radius epsilon). The paper clips
// the polygon against its exterior's triangles grown by epsilon, their
// corner arcs replaced by 3 tangent lines; occu offsets the polygon inwards
// by epsilon with Clipper (libpolyclipping), joins squared: at a reflex
// corner of the footprint the exact erosion boundary is an arc around the
// corner, and Clipper's square join is a tangent of that arc, outside the
// disc, so the result stays inside the exact erosion (a chord, as a round
// join with few segments would give, would not). Coordinates go through
// Clipper's integers at 1/10000 m; the offset adds one unit so their
// rounding never brings a point nearer than epsilon.
#pragma once

#include <vector>

#include "scene/scene.h"

namespace occu {

// The parts of `footprint` eroded by `epsilon` metres (a footprint may
// split in several, or vanish: an empty result), with the same heights.
// Throws std::invalid_argument for a negative or non-finite epsilon, or a
// footprint with fewer than 3 points or non-finite ones.
std::vector<PrismOccluder> shrink_footprint(const PrismOccluder &footprint, double epsilon);

// The union of the footprints grown by `margin` metres (every point within
// margin of one is inside; square joins, so corners reach a little
// farther), with the gaps between them narrower than `close_gaps` metres
// filled (a morphological closing), as outlines with holes; heights are
// not kept. Throws as shrink_footprint.
std::vector<PrismOccluder> grown_union(const std::vector<PrismOccluder> &footprints, double margin,
                                       double close_gaps = 0.0);

// Distance from p to the nearest point outside `footprint` (0 outside it):
// the reference the tests hold shrink_footprint to.
double depth_inside(const PrismOccluder &footprint, const glm::dvec2 &p);

// Signed area (positive counter-clockwise in (x, z)) of a closed polygon.
double signed_area(const std::vector<glm::dvec2> &polygon);
// Even-odd point in polygon (outline and holes).
bool inside(const PrismOccluder &footprint, const glm::dvec2 &p);

}  // namespace occu
