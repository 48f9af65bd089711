// SPDX-License-Identifier: MIT
// Which question a strategy that tests with the Occlusion Unit asks it:
// at tolerance 0 (adaptive_culling.h) only whether some fragment of a tile
// passed, which GL_MESAX_occlusion_unit_conservative answers without
// counting (spec/MESAX_occlusion_unit_conservative.txt; llvmpipe rejects
// whole bins on coarse depth); otherwise the counts NOHC and PHC. The
// setting `answer` declares it once for every family that tests so.
#pragma once

#include "culling/settings.h"
#include "gl/occlusion_unit.h"

namespace occu {

inline SettingSpec occlusion_answer_setting()
{
    return choice_setting("answer", {"conservative", "exact"},
                          "at tolerance 0 the unit is asked only whether some fragment of a tile passed "
                          "(GL_MESAX_occlusion_unit_conservative: llvmpipe rejects whole bins on coarse depth and "
                          "stops on a tile that passed), or asked to count as at other tolerances; the answers "
                          "are the same",
                          SettingSpec::Role::cost);
}

// The pass mode for a strategy of these settings at `tolerance`.
inline gl::OcclusionMode occlusion_question(const Settings &settings, double tolerance)
{
    return tolerance == 0.0 && settings.text("answer") == "conservative" ? gl::OcclusionMode::conservative
                                                                         : gl::OcclusionMode::brief;
}

}  // namespace occu
