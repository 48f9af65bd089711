// SPDX-License-Identifier: MIT
// Bartz, Meissner and Huettner, "Extending Graphics Hardware For Occlusion
// Queries In OpenGL" (1998): occlusion-driven rendering with the Occlusion
// Unit (GL_MESAX_occlusion_unit, gl/occlusion_unit.h).
//
// Section 3: the hierarchy is traversed front to back; a node's bounding
// box is rendered in GL_BRIEF_OCCLUSION_MESAX mode against the depth of
// what has been drawn so far; NOHC = 0 means occluded. Section 3.1's
// occlusion tiles let one pass test several boxes: one tile per box, the
// tile being the box's footprint. A tile counts every fragment that falls
// in it, whichever box it came from, so by default boxes share a pass only
// when their footprints are disjoint (passes=disjoint); with passes=shared
// overlapping boxes share passes too: another box's fragments in a tile
// can only make its box look visible, never occluded, so this stays
// conservative and trades culling for fewer passes.
//
// Section 5, adaptive culling: with tolerance t > 0 a box counts as
// occluded when NOHC <= t * PHC, i.e. when at most that fraction of its
// projection is visible; t = 0 is exact and conservative
// (culling/adaptive_culling.h, the rule chc's passes use too).
//
// Boxes without a footprint (they hold the eye or cross the near plane)
// are visible without a test (spec issue 13), and so are boxes whose
// footprint covers more than max-test-area of the viewport: testing them
// costs most (the unit counts every fragment of the box) and they are
// rarely hidden; their children are tested instead.
//
// proxy=triangles tests a leaf by drawing its own triangles in the pass
// instead of its box: boxes show above and beside occluders where what
// they hold does not; the triangles are exact (the rasterization that
// would draw them, with LEQUAL and an offset towards the eye), at the
// price of the leaf's vertex work in the pass.
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily occlusion_unit_family();

}  // namespace occu::strategies
