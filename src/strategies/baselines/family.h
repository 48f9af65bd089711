// SPDX-License-Identifier: MIT
// The references every occlusion strategy is measured against.
//   none   draws everything;
//   vfc    view-frustum culling only: the baseline of the occlusion
//          culling comparisons (Moeller and Haines, "Occlusion Culling
//          Algorithms", the general algorithm; Poon and Wang, section 6);
//   ideal  draws exactly the leaves the exact-visibility oracle sees in
//          the frame (evaluation/oracle.h): no culling strategy can draw
//          less without losing pixels, so its frame time is the floor of
//          any culled frame (the oracle's own time is not counted).
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily no_culling_family();
StrategyFamily frustum_culling_family();
StrategyFamily ideal_family();

}  // namespace occu::strategies
