#include "evaluation/side_by_side.h"

#include <chrono>

#include "gl/gl_headers.h"
#include "gl/state.h"

namespace occu {

TimedFrame draw_timed_frame(const SceneRenderer &renderer, const Hierarchy &hierarchy, Culler &culler,
                            const Frame &frame, const TraversalOptions &traversal)
{
    const auto start = std::chrono::steady_clock::now();
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl::load_camera(frame.camera);
    FrameStats stats = render_hierarchy(renderer, hierarchy, culler, frame, traversal);
    glFinish();
    return {std::move(stats), std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()};
}

TraversalPolicies::TraversalPolicies(const StrategyFamily &family, bool coherence_on, double min_gain)
{
    if (family.queries_rasterizer && coherence_on)
        coherence.emplace();
    if ((family.queries_rasterizer || family.costs_per_frame) && min_gain > 0.0) {
        SwitchOff::Settings s;
        s.min_gain = min_gain * family.switch_off_share;
        switch_off.emplace(s);
    }
}

TraversalOptions TraversalPolicies::options(std::size_t batch)
{
    TraversalOptions t;
    t.batch = batch;
    t.coherence = coherence ? &*coherence : nullptr;
    t.switch_off = switch_off ? &*switch_off : nullptr;
    return t;
}

}  // namespace occu
