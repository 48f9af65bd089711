// SPDX-License-Identifier: MIT
// One measurement of several culling strategies side by side, for every
// program that compares them (walkthrough, occu-random-views,
// occu-bench-no-occlusion, occu-bench-knobs): the strategies made from
// their names (culling/registry.h), each with its traversal policies,
// draw the same frames, frame by frame, and each frame is measured against
// the exact-visibility oracle (evaluation/oracle.h: culling efficiency, as
// Poon and Wang, section 6, compare with the exact visible set) and,
// where asked, against the unculled frame (evaluation/lost_pixels.h).
//
// Fair timing. Every strategy draws frame f before any draws frame f + 1,
// so that the machine's load, which drifts, weighs on all of them alike.
// The strategy that follows another's frame (or the oracle's, or the
// unculled frame's) pays for what that left behind in the caches and the
// rasterizer, so the order is shuffled anew for every frame from a fixed
// seed: a rotation, which keeps neighbours together, made `ideal` follow
// `vfc`'s long frame in every frame and measured it about 20% slower than
// it is. A frame is timed from its clear to glFinish; the oracle, the
// unculled frame and the lost pixels are drawn untimed. The minor page
// faults the process takes while a strategy draws (getrusage) are counted
// per frame: freed memory faulted in again costs time that depends on the
// process, not on the strategy, so the session keeps freed memory in the
// process (SessionOptions::allocator, evaluation/allocator.h).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "culling/databases.h"
#include "evaluation/allocator.h"
#include "culling/registry.h"
#include "evaluation/lost_pixels.h"
#include "evaluation/oracle.h"
#include "evaluation/scene_setup.h"
#include "render/scene_renderer.h"
#include "traversal/policies.h"
#include "traversal/traversal.h"

namespace occu {

namespace gl {
class OffscreenContext;
}

// A strategy's traversal policies (traversal/policies.h), those its family
// wants (StrategyFamily::traversal): temporal coherence when `coherence`,
// switch-off when `switch_off` (the least share of triangles occlusion
// tests must cull) is above 0.
struct TraversalPolicies {
    std::optional<VisibleNodeList> coherence;
    std::optional<SwitchOff> switch_off;

    TraversalPolicies() = default;
    TraversalPolicies(const StrategyFamily &family, bool coherence, double switch_off);
    // The options of one frame: `batch` nodes at a time, with these policies.
    TraversalOptions options(std::size_t batch);
};

struct SessionOptions {
    std::size_t batch = 32;      // nodes tested together, where a strategy is not given its own
    bool coherence = true;       // temporal coherence, for the families it applies to
    double switch_off = 0.5;     // the switch-off's least gain, for the families it applies to; 0: never
    bool oracle = true;          // the oracle's answer for every frame (efficiency; `ideal` needs it)
    // Whose frames are compared with the unculled frame (lost pixels):
    // nobody's, the approximate strategies' (the conservative ones lose
    // none: their tests prove it), or everybody's.
    enum class PixelCheck { none, approximate, all };
    PixelCheck lost_pixels = PixelCheck::approximate;
    std::uint64_t order_seed = 1998;   // the strategies' shuffled order in each frame
    // Applied to the process when the session is made (evaluation/allocator.h).
    AllocatorPolicy allocator = AllocatorPolicy::keep_freed;
    float clear_colour[4] = {0.55f, 0.7f, 0.9f, 1.0f};
    // How frames look (render/scene_renderer.h): the colour pass alone
    // textures; what a strategy draws to cull never does.
    Look look = Look::flat;
    // What times each strategy's setup and test ms (TraversalOptions::clock,
    // traversal/clock.h); a frame's ms is on the wall clock whatever this
    // says, since llvmpipe draws it on threads of its own.
    Clock culling_clock = Clock::wall;
    // Makes or finds the databases the strategies read and were not given
    // (culling/databases.h); none: a strategy that requires one and was
    // not given it refuses to be made.
    DatabaseProvider *databases = nullptr;
};

// What one strategy measured over the frames it drew.
struct Measured {
    std::vector<double> ms;                   // per frame, clear to finish
    std::vector<std::uint32_t> nodes_tested;  // per frame
    // Sums over the frames.
    double triangles = 0, passes = 0, setup_ms = 0, test_ms = 0;   // setup, test: SessionOptions::culling_clock
    std::uint64_t occluded = 0, occluded_culled = 0, visible_culled = 0;   // leaves, against the oracle
    std::uint64_t lost_pixels = 0, tied_pixels = 0;   // evaluation/lost_pixels.h, where checked
    std::uint64_t page_faults = 0;

    std::size_t frames() const { return ms.size(); }
    double mean_ms() const;
    double median_ms() const;
    double least_ms() const;
    // A sum over the frames, per frame (0 without frames).
    double per_frame(double sum) const { return ms.empty() ? 0.0 : sum / double(ms.size()); }
    // Occluded leaves culled / occluded leaves, in percent; nothing when no
    // leaf was occluded (or no oracle ran).
    std::optional<double> efficiency_percent() const;
    // Another run's frames, pooled with these (rounds of a route).
    void pool(const Measured &other);
};

// A strategy in a session: made once, its policies kept across frames.
struct SessionStrategy {
    std::string label;       // how results name it
    Strategy strategy;
    TraversalPolicies policies;
    std::size_t batch = 32;
    bool checks_pixels = false;
    Measured measured;
};

// One strategy's frame, as a session's observer sees it (after it was
// drawn and measured; the context holds its pixels).
struct StrategyFrame {
    std::size_t index = 0;   // the camera's, in the walk
    const Frame *frame = nullptr;   // its camera and the oracle's answer (frame->truth; null without oracle)
    double ms = 0.0;
    FrameStats stats;
    CullingQuality quality;  // against the oracle (zero without it)
    bool pixels_checked = false;
    PixelLoss loss;          // where checked
    std::uint64_t page_faults = 0;
};

class MeasurementSession {
public:
    // Over `scene`, into `context` (current, its size the frames'), which
    // must outlive the session.
    MeasurementSession(const SceneSetup &scene, gl::OffscreenContext &context, const SessionOptions &options = {});
    ~MeasurementSession();
    MeasurementSession(const MeasurementSession &) = delete;
    MeasurementSession &operator=(const MeasurementSession &) = delete;

    // Makes the strategy `spec` (NAME[:key=value...]) with the `common`
    // settings that it has and the databases the options' provider gives
    // it, named `label` in the results (default: spec), traversed `batch`
    // nodes at a time (0: the options'). Throws std::invalid_argument as
    // make_strategy does (a scene the family refuses among it), and when
    // the strategy needs the oracle and the session has none; a strategy
    // that refuses its settings throws what it throws.
    SessionStrategy &add(const std::string &spec, const std::vector<std::string> &common = {},
                         const std::string &label = {}, std::size_t batch = 0);
    // A strategy made by the caller (a culler of a test's own, such as one
    // broken on purpose), named `label`, traversed `batch` nodes at a time
    // (0: the options'); its choice says its family's policies and whether
    // its pixels are checked. Throws std::invalid_argument when it needs
    // the oracle and the session has none.
    SessionStrategy &add(Strategy strategy, const std::string &label, std::size_t batch = 0);
    // add(), unless the strategy's family refuses the session's scene
    // (StrategyFamily::refusal): then it adds nothing and returns why
    // (empty: added), so that a run over several scenes leaves out, with
    // its reason, what a scene cannot serve.
    std::string add_unless_refused(const std::string &spec, const std::vector<std::string> &common = {},
                                   const std::string &label = {});

    using Observer = std::function<void(const SessionStrategy &, const StrategyFrame &)>;
    // One frame of `camera` by every strategy, in this frame's shuffled
    // order; `index` names it to the observer, called after each strategy's
    // frame.
    void measure(std::size_t index, const Camera &camera, const Observer &observer = {});
    // measure() for every camera, with a progress bar `what` on a terminal.
    void walk(const std::vector<Camera> &cameras, const std::string &what, const Observer &observer = {});

    std::deque<SessionStrategy> &strategies() { return strategies_; }
    const std::deque<SessionStrategy> &strategies() const { return strategies_; }
    const SceneSetup &scene() const { return scene_; }
    const SceneRenderer &renderer() const { return renderer_; }
    StrategyContext context() const { return {scene_.scene(), scene_.hierarchy(), renderer_}; }
    bool has_oracle() const { return oracle_.has_value(); }
    Clock culling_clock() const { return options_.culling_clock; }
    int width() const { return width_; }
    int height() const { return height_; }

    // The mean frame ms of `family` at its defaults (vfc, ideal: the
    // references of the ratios); 0 when it did not run.
    double reference_ms(const std::string &family) const;
    // "label: note" for each strategy that has one (Culler::note).
    std::vector<std::string> notes() const;

private:
    void set_frame_state() const;
    std::vector<std::size_t> shuffled_order();

    SceneSetup scene_;
    gl::OffscreenContext &gl_;
    SessionOptions options_;
    int width_, height_;
    SceneRenderer renderer_;
    std::optional<Oracle> oracle_;
    Strategy unculled_strategy_;
    std::deque<SessionStrategy> strategies_;
    std::uint64_t order_state_;
    std::vector<std::uint8_t> unculled_, culled_;
};

}  // namespace occu
