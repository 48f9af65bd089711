// SPDX-License-Identifier: MIT
// A culler whose tests are issued in batches and answered later, while
// drawing goes on: hardware occlusion queries read when their results are
// available, as coherent hierarchical culling uses them (Bittner et al.
// 2004; Mattausch et al. 2008). A traversal of its own drives it
// (strategies/bittner_coherent_hierarchical_culling/): it decides what to
// test and when to wait; the culler only issues, answers and draws under
// the condition of an answer it has not read.
//
// The conventions are Culler's (culling/culler.h): the same Frame, the
// same footprints, answers visible or occluded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "culling/culler.h"
#include "geometry/pixel_rect.h"

namespace occu {

// One test: whether anything in `boxes` (a node's box, or the boxes of its
// descendants: Mattausch et al.'s tight bounds) may be seen.
struct AsyncTest {
    std::uint32_t node = 0;   // whose visibility it decides
    // In: the boxes to test. prepare() turns them into what the culler
    // draws for them.
    std::vector<Aabb> boxes;
    // Out (prepare): the screen rectangle the test covers.
    PixelRect area;
};

class AsyncCuller {
public:
    using Batch = std::size_t;   // a batch in flight, until release()

    virtual ~AsyncCuller() = default;
    // Tests after this are against `frame` and the depth drawn into it.
    virtual void begin_frame(const Frame &frame) = 0;
    // At most this many tests in one batch.
    virtual std::size_t batch_capacity() const = 0;
    // Whether tests whose areas overlap share a batch (where they do, a
    // test may answer visible for another's boxes, never occluded).
    virtual bool shares_overlapping() const = 0;
    // Makes `test` ready to issue in this frame; false when it cannot be
    // tested (a box without a footprint): its node is visible untested.
    virtual bool prepare(AsyncTest &test) const = 0;
    // Issues `tests` as one batch, against the depth drawn so far; their
    // answers come later.
    virtual Batch issue(std::vector<AsyncTest> tests) = 0;
    // Whether the batch's answers are there (never waits).
    virtual bool ready(Batch batch) = 0;
    // Test k's answer, visible or occluded; waits for the batch if need be.
    // For a test drawn under its condition, the condition's answer.
    virtual Visibility answer(Batch batch, std::size_t k) = 0;
    // Calls `draw` under the condition that test k finds its node visible,
    // without waiting for the answer (the GL decides where it can). False
    // when the culler knows already that the condition fails and did not
    // call `draw`.
    virtual bool draw_if_visible(Batch batch, std::size_t k, const std::function<void()> &draw) = 0;
    // The batch's answers are no longer needed.
    virtual void release(Batch batch) = 0;
    virtual CullerStats stats() const = 0;
    // As Culler::note.
    virtual std::string note() const { return {}; }
};

}  // namespace occu
