// SPDX-License-Identifier: MIT
// Adaptive culling on occlusion counts (Bartz, Meissner and Huettner,
// "Extending Graphics Hardware For Occlusion Queries In OpenGL", 1998,
// section 5): a tile whose non-occlusion hits (NOHC) are at most
// `tolerance` of its projection hits (PHC) is occluded; at tolerance 0,
// only a tile with none. The rule of every strategy that reads the
// Occlusion Unit's records (gl/occlusion_unit.h), synchronous or not.
// Counters saturate at 2^32 - 1 (the spec's issue 5): a saturated PHC
// understates the fragments and a saturated NOHC overstates their share,
// so saturation can only keep a node visible, never cull one the exact
// counts would keep.
#pragma once

#include <cstdint>

namespace occu {

inline bool adaptive_culling_occludes(std::uint32_t nohc, std::uint32_t phc, double tolerance)
{
    return tolerance == 0.0 ? nohc == 0 : double(nohc) <= tolerance * double(phc);
}

}  // namespace occu
