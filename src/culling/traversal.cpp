#include "culling/traversal.h"

#include <chrono>
#include <queue>

#include <glm/gtc/type_ptr.hpp>

namespace occu {

namespace {
float distance_to(const Aabb &box, const glm::vec3 &p)
{
    const glm::vec3 d = glm::max(glm::max(box.min - p, p - box.max), glm::vec3(0.0f));
    return glm::length(d);
}
}  // namespace

void load_camera(const Camera &camera)
{
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixf(glm::value_ptr(camera.projection()));
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixf(glm::value_ptr(camera.view()));
}

FrameStats render_hierarchy(const SceneRenderer &renderer, const Hierarchy &hierarchy, Culler &culler,
                            const Camera &camera, const TraversalOptions &options, Coherence *coherence)
{
    FrameStats stats;
    const auto &nodes = hierarchy.nodes();
    std::vector<std::uint8_t> visible_now;
    if (coherence) {
        coherence->visible_last_frame.resize(nodes.size(), 0);
        visible_now.assign(nodes.size(), 0);
    }
    const Frustum frustum(camera.view_projection());
    // Occlusion switched off: this frame tests the frustum only, unless it probes.
    // A probe frame tests afresh (up to its pass budget), so that it
    // measures what occlusion culling would gain now.
    const bool off = coherence && coherence->occlusion_off;
    const bool probe = off && coherence->frames_to_probe <= 1;
    if (off && !probe)
        --coherence->frames_to_probe;
    bool switched_off = off && !probe;
    // A probe cut short by its budget judges by what it saw before the cut:
    // triangles occluded against triangles drawn up to then.
    bool budget_spent = false, cut_pending = false;
    std::uint64_t triangles_at_cut = 0, occluded_at_cut = 0;
    stats.occlusion_tested = !switched_off;
    // Taken as visible without a test: visible last frame and not due.
    auto assumed_visible = [&](std::uint32_t n) {
        return switched_off ||
               (!probe && coherence && coherence->visible_last_frame[n] &&
                (coherence->frame + n) % std::max<std::uint32_t>(1, coherence->retest_period) != 0);
    };
    using Entry = std::pair<float, std::uint32_t>;   // distance, node
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> front;
    front.push({distance_to(nodes[0].bounds, camera.position), 0});
    using Clock = std::chrono::steady_clock;
    auto timed = [](double &ms, auto &&work) {
        const auto start = Clock::now();
        work();
        ms += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    };
    timed(stats.setup_ms, [&] { culler.begin_frame(camera); });

    // Below a visible_subtree answer nodes are drawn without occlusion tests.
    // Sized on the first such answer: strategies that never give one pay nothing.
    std::vector<std::uint8_t> untested;
    auto is_untested = [&untested](std::uint32_t n) { return !untested.empty() && untested[n]; };
    // What a node's visibility leads to: a visible leaf is drawn, a visible
    // inner node's children join the front.
    auto settle = [&](std::uint32_t node, Visibility visibility) {
        const HierarchyNode &n = nodes[node];
        const bool subtree = visibility == Visibility::visible_subtree;
        if (coherence && (visibility == Visibility::visible || subtree))
            visible_now[node] = 1;
        if (visibility == Visibility::view_culled) {
            ++stats.nodes_view_culled;
        } else if (visibility == Visibility::occluded) {
            ++stats.nodes_occluded;
            stats.triangles_occluded += n.subtree_triangles;
        } else if (n.leaf()) {
            stats.triangles += renderer.draw_leaf(node);
            ++stats.leaves_drawn;
            stats.drawn.push_back(node);
            culler.rendered(n.bounds);
        } else {
            if (subtree && untested.empty())
                untested.assign(nodes.size(), 0);
            for (std::uint32_t c = 0; c < n.child_count; ++c) {
                if (!untested.empty())
                    untested[n.first_child + c] = subtree;
                front.push({distance_to(nodes[n.first_child + c].bounds, camera.position), n.first_child + c});
            }
        }
    };
    std::vector<std::uint32_t> batch;
    std::vector<Aabb> boxes;
    std::vector<Visibility> results;
    while (!front.empty()) {
        batch.clear();
        boxes.clear();
        // Nodes taken as visible without a test are drawn (or opened) at
        // once, before the batch is tested: with temporal coherence the
        // previous frame's visible leaves are then in the depth buffer
        // when the nodes behind them are tested, whatever the batch size.
        while (!front.empty() && batch.size() < std::max<std::size_t>(1, options.batch)) {
            const std::uint32_t n = front.top().second;
            front.pop();
            if ((assumed_visible(n) || is_untested(n)) && frustum.classify(nodes[n].bounds) != Frustum::Side::outside) {
                settle(n, is_untested(n) ? Visibility::visible_subtree : Visibility::visible);
                continue;
            }
            batch.push_back(n);
            boxes.push_back(nodes[n].bounds);
        }
        timed(stats.test_ms, [&] { culler.test_nodes(hierarchy, batch, boxes, results); });
        stats.nodes_tested += std::uint32_t(batch.size());
        if (probe && !switched_off && culler.passes() >= coherence->probe_pass_budget) {
            switched_off = true;   // the probe has seen enough; the rest as when off
            budget_spent = true;
            cut_pending = true;
        }
        for (std::size_t i = 0; i < batch.size(); ++i)
            settle(batch[i], results[i]);
        if (cut_pending) {   // this batch's results are in: the probe's view ends here
            triangles_at_cut = stats.triangles;
            occluded_at_cut = stats.triangles_occluded;
            cut_pending = false;
        }
    }
    stats.passes = culler.passes();
    if (coherence) {
        coherence->visible_last_frame.swap(visible_now);
        if (stats.occlusion_tested) {
            const bool was_off = coherence->occlusion_off;
            const double drawn = double(budget_spent ? triangles_at_cut : stats.triangles);
            const double occluded = double(budget_spent ? occluded_at_cut : stats.triangles_occluded);
            coherence->occlusion_off = occluded < double(coherence->switch_off_fraction) * drawn;
            if (coherence->occlusion_off) {
                // Switching off waits the base period; a probe that finds
                // occlusion still not worth it waits twice as long as before.
                const std::uint32_t base = std::max<std::uint32_t>(1, coherence->probe_period);
                coherence->probe_wait = was_off ? std::min(std::max(base, coherence->max_probe_period),
                                                           2 * std::max(base, coherence->probe_wait))
                                                : base;
                coherence->frames_to_probe = coherence->probe_wait;
            }
        }
        ++coherence->frame;
    }
    return stats;
}

}  // namespace occu
