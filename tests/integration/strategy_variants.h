// SPDX-License-Identifier: MIT
// How the integration tests run strategies: through the measurement
// session (evaluation/measurement_session.h), which draws every
// strategy's frame of a camera and counts the visible pixels it lost by
// the rule of evaluation/lost_pixels.h, as occu-random-views does; over
// the registry's conservative names and the variants each family declares
// for testing (StrategyTestVariant, culling/registry.h), so that a shared
// test names no family's settings.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "culling/databases.h"
#include "culling/registry.h"
#include "evaluation/measurement_session.h"

namespace occu::integration {

// Every conservative name of the registry (families and presets) in
// batches of 16 without policies across frames, then every family's test
// variants.
std::vector<StrategyTestVariant> conservative_test_variants();

// How results name a variant: "SPEC/BATCH", then "/coherent" and
// "/probes" for its policies across frames.
std::string variant_label(const StrategyTestVariant &variant);

// A session that checks every strategy's frames against the unculled
// frame: a clear colour of zero bytes (an empty frame is all zero), no
// policies across frames but those a variant asks for, the C library's
// allocator, the databases strategies require from `databases` (may be
// null).
SessionOptions checking_session_options(DatabaseProvider *databases = nullptr);

// Adds `variant` to `session`, named by variant_label, with its batch and
// policies; `common` ("key=value") for every strategy that has the key.
// Throws as MeasurementSession::add does (a family that refuses the
// session's scene among it).
SessionStrategy &add_variant(MeasurementSession &session, const StrategyTestVariant &variant,
                             const std::vector<std::string> &common = {});

// Pixels in which a strategy's frame differs from the unculled frame: the
// visible pixels it lost and, where it did not order the frame itself,
// those it differs in through depth ties from the common traversal's
// unculled frame (evaluation/lost_pixels.h). Zero where it equals it.
inline std::uint64_t differing_pixels(const StrategyFrame &frame)
{
    return frame.loss.lost + frame.loss.tied;
}

// The leaves the oracle sees that the frame did not draw, for a failure's
// message (" none" without any, or without the oracle's answer).
std::string visible_leaves_not_drawn(const StrategyFrame &frame);

// Checks each variant's draws_at_most against the triangles the session's
// strategies drew over all their frames (a failure names both sides);
// returns how many claims it checked.
std::size_t expect_declared_bounds(const MeasurementSession &session,
                                   const std::vector<StrategyTestVariant> &variants);

}  // namespace occu::integration
