// SPDX-License-Identifier: MIT
// Bartz et al.'s adaptive culling rule (section 5) on counts near and at
// 2^32 - 1, where the unit's counters saturate (spec issue 5): saturation
// can keep a node visible that the exact counts would cull, never the
// reverse. The exact counts here are 64-bit; the unit reports them
// saturated to 32 bits.
#include "culling/adaptive_culling.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>

using occu::adaptive_culling_occludes;

namespace {

std::uint32_t saturated(std::uint64_t count)
{
    return count > 0xffffffffull ? 0xffffffffu : std::uint32_t(count);
}

}  // namespace

TEST(AdaptiveCulling, ExactAtToleranceZero)
{
    EXPECT_TRUE(adaptive_culling_occludes(0, 0xffffffffu, 0.0));
    EXPECT_FALSE(adaptive_culling_occludes(1, 0xffffffffu, 0.0));
    EXPECT_FALSE(adaptive_culling_occludes(0xffffffffu, 0xffffffffu, 0.0));
}

TEST(AdaptiveCulling, SaturatedCountsNeverCullWhatExactCountsKeep)
{
    std::mt19937_64 rng(2026);
    int kept_by_saturation = 0;
    for (int i = 0; i < 200000; ++i) {
        // Counts around 2^32: a frame of 4096 x 4096 pixels with a few
        // hundred layers of depth complexity reaches them in one tile.
        const std::uint64_t phc = (std::uint64_t(1) << 31) + rng() % (std::uint64_t(1) << 34);
        const std::uint64_t nohc = rng() % (phc + 1);
        const double tolerance = (i % 4) * 0.1;
        const bool exact = tolerance == 0.0 ? nohc == 0 : double(nohc) <= tolerance * double(phc);
        const bool reported = adaptive_culling_occludes(saturated(nohc), saturated(phc), tolerance);
        ASSERT_TRUE(!reported || exact) << "culled with NOHC " << nohc << " PHC " << phc << " tolerance " << tolerance;
        kept_by_saturation += exact && !reported;
    }
    EXPECT_GT(kept_by_saturation, 0) << "the cases reach the saturated counters";
}
