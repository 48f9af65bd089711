// SPDX-License-Identifier: MIT
// The asynchronous culler of coherent hierarchical culling on the Occlusion
// Unit (culling/async_culler.h): a batch is one pass of
// GL_MESAX_occlusion_unit_async with one tile per test (its area), read when
// its records are ready; a test draws proxy boxes (render/occlusion_proxy.h)
// and its tile is the union of their footprints; a conditional draw is
// conditional rendering on the test's tile (gl/occlusion_unit.h; emulated on
// glRenderMode, with the same results and every wait in the pass's end,
// where the context lacks the extension).
//
// Tiles of a pass may overlap (passes=shared): another test's fragments in
// a tile can only make its node look visible, never occluded (as ou's
// passes=shared). A test is occluded when NOHC <= tolerance * PHC (Bartz
// et al. 1998, section 5, as ou's tolerance; CHC++'s visibility threshold).
#pragma once

#include <memory>

#include "culling/async_culler.h"
#include "culling/settings.h"

namespace occu::strategies {

// Its settings: tolerance, passes (disjoint, shared) and batch (tiles a pass).
std::unique_ptr<AsyncCuller> make_occlusion_unit_async_culler(const Settings &settings);

}  // namespace occu::strategies
