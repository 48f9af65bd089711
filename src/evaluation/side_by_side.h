// Frames of several strategies side by side (walkthrough, occu-bench-knobs):
// one strategy's frame timed from clear to finish, and the traversal
// policies a family's frames run with.
#pragma once

#include <algorithm>
#include <optional>
#include <vector>

#include "culling/registry.h"
#include "traversal/policies.h"
#include "traversal/traversal.h"

namespace occu {

// A frame drawn by one strategy, timed from clear to finish.
struct TimedFrame {
    FrameStats stats;
    double ms = 0.0;
};

// Clears colour and depth, loads the frame's camera, renders the hierarchy
// with `culler` and waits for it (glFinish); into the current context.
TimedFrame draw_timed_frame(const SceneRenderer &renderer, const Hierarchy &hierarchy, Culler &culler,
                            const Frame &frame, const TraversalOptions &traversal);

// A strategy's traversal policies (traversal/policies.h): temporal
// coherence for the families whose tests query the rasterizer (when
// `coherence`), switch-off for those and for the families whose CPU work
// costs time every frame (when `switch_off`, the least share of triangles
// occlusion tests must cull, is above 0).
struct TraversalPolicies {
    std::optional<VisibleNodeList> coherence;
    std::optional<SwitchOff> switch_off;

    TraversalPolicies() = default;
    TraversalPolicies(const StrategyFamily &family, bool coherence, double switch_off);
    // The options of one frame: `batch` nodes at a time, with these policies.
    TraversalOptions options(std::size_t batch);
};

// The mean and the median of a strategy's frame times (0 without frames).
inline double mean_ms(const std::vector<double> &ms)
{
    double t = 0;
    for (double x : ms)
        t += x;
    return ms.empty() ? 0.0 : t / double(ms.size());
}

inline double median_ms(std::vector<double> ms)
{
    std::sort(ms.begin(), ms.end());
    return ms.empty() ? 0.0 : ms[ms.size() / 2];
}

}  // namespace occu
