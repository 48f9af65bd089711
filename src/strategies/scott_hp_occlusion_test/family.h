// SPDX-License-Identifier: MIT
// The HP occlusion test: Hewlett-Packard's occlusion culling in the
// VISUALIZE fx graphics hardware (Scott, Olsen and Gannett, "An Overview
// of the VISUALIZE fx Graphics Accelerator Hardware", Hewlett-Packard
// Journal, May 1998), as Moeller and Haines, "Occlusion Culling
// Algorithms", section "VISUALIZE fx's Hardware Implementation", describe
// it; Bartz et al. 1998 (section 2, reference [8]) cite its OpenGL
// extension. Before a complex object is drawn, the pixels of its bounding
// box are scan-converted and depth tested without being drawn; if none
// would be visible the object is culled. The answer is one flag per box,
// so every box is its own query and the renderer waits for each, front to
// back; the Occlusion Unit (strategies/bartz_occlusion_unit) answers many
// boxes per pass instead.
//   hp  (hp_occlusion_test_culler.cpp) each box is one occlusion query
//       (ARB_occlusion_query, the HP test's successor in core GL), asked
//       for the flag alone where the context offers it
//       (GL_ANY_SAMPLES_PASSED_CONSERVATIVE, else GL_ANY_SAMPLES_PASSED,
//       else the count GL_SAMPLES_PASSED: gl/occlusion_query.h), its proxy
//       drawn with colour and depth writes off; a batch issues its queries and then reads them,
//       so the rasterizer works through the batch before the first answer
//       is needed. Boxes without a footprint (they hold the eye or cross
//       the near plane) are visible untested. proxy=triangles queries a
//       leaf with its own triangles instead of its box, as the Occlusion
//       Unit's proxy=triangles does (strategies/bartz_occlusion_unit): a
//       box shows above and beside occluders where what it holds does not;
//       the triangles, drawn as they would be, are exact, for the leaf's
//       vertex work in the query.
#pragma once

#include "culling/registry.h"

namespace occu::strategies {

StrategyFamily hp_occlusion_test_family();

}  // namespace occu::strategies
