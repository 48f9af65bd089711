// SPDX-License-Identifier: MIT
#include "traversal/traversal.h"

#include <algorithm>
#include <queue>
#include <stdexcept>
#include <string>

namespace occu {

namespace {

float distance_to(const Aabb &box, const glm::vec3 &p)
{
    const glm::vec3 d = glm::max(glm::max(box.min - p, p - box.max), glm::vec3(0.0f));
    return glm::length(d);
}

// One frame's traversal: the front of nodes ordered by distance, what each
// answer leads to, and the nodes drawn without a test.
class FrameTraversal {
public:
    FrameTraversal(const SceneRenderer &renderer, const Hierarchy &hierarchy, Culler &culler, const Frame &frame,
                   const TraversalOptions &options)
        : renderer_(renderer), nodes_(hierarchy.nodes()), culler_(culler), frame_(frame), options_(options),
          watch_(options.clock), count_occluded_(std::any_of(options.policies.begin(), options.policies.end(),
                                      [](const TraversalPolicy *p) { return p->reads_triangles_occluded(); }))
    {
    }

    FrameStats run()
    {
        const FrameOutlook outlook{nodes_, [this] { return in_frustum_triangles(0, Frustum::all_planes); }};
        FrameTesting testing = FrameTesting::full;
        for (TraversalPolicy *p : options_.policies)
            testing = std::min(testing, p->begin_frame(outlook));
        testing_ = testing != FrameTesting::off;
        // A strategy that orders the frame itself runs its own traversal
        // while it tests; switched off, it is not called at all and the
        // frame below is view-frustum culling alone, as for any strategy;
        // its probes are the common traversal's, through its test().
        if (OwnTraversal *own = own_traversal(culler_); own && testing == FrameTesting::full)
            return run_ordered(*own);
        frame_testing_ = testing;
        stats_.occlusion_tested = testing_;
        // A frame switched off costs the strategy nothing: no occluders
        // drawn, no tests (the traversal culls to the frustum itself).
        if (testing == FrameTesting::probe) {
            Frame probe = frame_;
            probe.probe = true;
            watch_.time(stats_.setup_ms, [&] { culler_.begin_frame(probe); });
        }
        else if (testing_) {
            watch_.time(stats_.setup_ms, [&] { culler_.begin_frame(frame_); });
        }
        push(0);
        std::vector<NodeTest> batch;
        while (!front_.empty()) {
            next_batch(batch);
            if (!batch.empty()) {
                watch_.time(stats_.test_ms, [&] { culler_.test(batch); });
                stats_.nodes_tested += std::uint32_t(batch.size());
            }
            for (const NodeTest &t : batch)
                settle(t.node, t.result, t.test_below);
            // A policy may stop the tests after a batch (a probe whose
            // budget is spent: it judges by what it saw up to here).
            if (testing_)
                for (TraversalPolicy *p : options_.policies)
                    if (p->stop_testing(stats_))
                        testing_ = false;
        }
        stats_.passes = culler_.stats().passes;
        draw_see_through();
        for (TraversalPolicy *p : options_.policies)
            p->end_frame(stats_);
        return std::move(stats_);
    }

private:
    // A strategy that walks the hierarchy itself (OwnTraversal): it
    // traverses and tests, this draws and counts. Its test time is the
    // traversal's time less the drawing's.
    class Sink final : public FrameSink {
    public:
        explicit Sink(FrameTraversal &t) : t_(t) {}
        void draw_leaf(std::uint32_t node) override
        {
            if (!t_.nodes_.at(node).leaf())
                throw std::logic_error("a strategy drew inner node " + std::to_string(node) + " as a leaf");
            // On the traversal's clock, whose time less this is the test's.
            t_.watch_.time(draw_ms, [&] { t_.settle(node, Visibility::visible, true); });
        }
        void draw_leaf_conditionally(std::uint32_t node) override
        {
            draw_leaf(node);
            ++t_.stats_.leaves_conditional;
        }
        void cull(std::uint32_t node, Visibility why) override { t_.settle(node, why, true); }
        void tested(std::uint32_t count) override { t_.stats_.nodes_tested += count; }
        double draw_ms = 0.0;

    private:
        FrameTraversal &t_;
    };

    FrameStats run_ordered(OwnTraversal &own)
    {
        ordered_ = true;
        watch_.time(stats_.setup_ms, [&] { culler_.begin_frame(frame_); });
        Sink sink(*this);
        double traverse_ms = 0.0;
        watch_.time(traverse_ms, [&] { own.traverse(sink); });
        stats_.test_ms = std::max(0.0, traverse_ms - sink.draw_ms);
        stats_.passes = culler_.stats().passes;
        draw_see_through();
        // Judged as any tested frame is: the triangles its answers culled
        // against those it drew.
        for (TraversalPolicy *p : options_.policies)
            p->end_frame(stats_);
        return std::move(stats_);
    }

    // The frame's last pass (render/scene_renderer.h): the see-through
    // triangles of the leaves drawn, after every test, so that no test
    // found a box occluded by a see-through surface.
    void draw_see_through() { stats_.triangles += renderer_.draw_see_through(stats_.drawn, frame_.camera.position); }

    void push(std::uint32_t node) { front_.push({distance_to(nodes_[node].bounds, frame_.camera.position), node}); }

    bool untested(std::uint32_t node) const { return !untested_.empty() && untested_[node]; }

    // How node n is tested: not at all in a frame that does not test (or
    // no longer does); taken as visible below a "do not test below"
    // answer; else as the policies say.
    NodeTesting node_testing(std::uint32_t n) const
    {
        if (!testing_)
            return NodeTesting::skipped;
        NodeTesting how = untested(n) ? NodeTesting::assumed_visible : NodeTesting::test;
        for (const TraversalPolicy *p : options_.policies)
            how = std::max(how, p->node_testing(n, nodes_[n].leaf(), frame_testing_));
        return how;
    }

    // Takes nodes off the front until `batch` holds options.batch nodes to
    // test. Nodes taken as visible without a test are drawn (or opened) at
    // once, before the batch is tested: with temporal coherence the
    // previous frame's visible leaves are then in the depth buffer when the
    // nodes behind them are tested, whatever the batch size.
    void next_batch(std::vector<NodeTest> &batch)
    {
        batch.clear();
        const std::size_t size = std::max<std::size_t>(1, options_.batch);
        while (!front_.empty() && batch.size() < size) {
            const std::uint32_t n = front_.top().second;
            front_.pop();
            const NodeTesting how = node_testing(n);
            if (how != NodeTesting::test) {
                const bool outside = frame_.frustum.classify(nodes_[n].bounds) == Frustum::Side::outside;
                if (!outside || how == NodeTesting::skipped) {
                    settle(n, outside ? Visibility::view_culled : Visibility::visible, !untested(n));
                    continue;
                }
            }
            NodeTest t;
            t.node = n;
            t.box = nodes_[n].bounds;
            t.leaf = nodes_[n].leaf();
            batch.push_back(t);
        }
    }

    // What a node's answer leads to: a visible leaf is drawn, a visible
    // inner node's children join the front.
    void settle(std::uint32_t node, Visibility visibility, bool test_below)
    {
        const HierarchyNode &n = nodes_[node];
        if (visibility == Visibility::view_culled) {
            ++stats_.nodes_view_culled;
            return;
        }
        if (visibility == Visibility::occluded) {
            ++stats_.nodes_occluded;
            for (TraversalPolicy *p : options_.policies)
                p->occluded(node);
            if (count_occluded_)
                stats_.triangles_occluded += in_frustum_triangles(node, Frustum::all_planes);
            return;
        }
        if (!ordered_)
            for (TraversalPolicy *p : options_.policies)
                p->visible(node);
        if (n.leaf()) {
            stats_.triangles += renderer_.draw_leaf(node);
            ++stats_.leaves_drawn;
            stats_.drawn.push_back(node);
            if (testing_)
                culler_.rendered(node);
            return;
        }
        // Sized on the first "do not test below": strategies that never
        // give one pay nothing.
        if (!test_below && untested_.empty())
            untested_.assign(nodes_.size(), 0);
        for (std::uint32_t c = 0; c < n.child_count; ++c) {
            if (!untested_.empty())
                untested_[n.first_child + c] = !test_below;
            push(n.first_child + c);
        }
    }

    // The triangles of `node`'s subtree that view-frustum culling would have
    // drawn: what culling it as occluded saved. A node reaching out of the
    // frustum may hold leaves wholly outside it, and a test may find such a
    // node occluded where its part in the frustum holds nothing that shows
    // (chc does on the field, scene/field.h, whose leaves at the frame's
    // edges show nothing); counted whole, they would look like a gain to
    // the switch-off where there is none. Only nodes crossing a frustum
    // plane are opened, and their children are classified against the
    // planes they cross alone (`crossing`, Frustum::classify), so the cost
    // stays at the frame's edges.
    std::uint64_t in_frustum_triangles(std::uint32_t node, unsigned crossing) const
    {
        const HierarchyNode &n = nodes_[node];
        switch (frame_.frustum.classify(n.bounds, crossing)) {
        case Frustum::Side::inside:
            return n.subtree_triangles;
        case Frustum::Side::outside:
            return 0;
        default:
            break;
        }
        if (n.leaf())
            return n.triangle_count;
        std::uint64_t t = 0;
        for (std::uint32_t c = 0; c < n.child_count; ++c)
            t += in_frustum_triangles(n.first_child + c, crossing);
        return t;
    }

    const SceneRenderer &renderer_;
    const std::vector<HierarchyNode> &nodes_;
    Culler &culler_;
    const Frame &frame_;
    const TraversalOptions &options_;
    using Entry = std::pair<float, std::uint32_t>;   // distance, node
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> front_;
    std::vector<std::uint8_t> untested_;   // below a "do not test below" answer
    bool testing_ = true;    // the frame tests occlusion (until a policy stops it)
    FrameTesting frame_testing_ = FrameTesting::full;
    bool ordered_ = false;   // the culler orders the frame (run_ordered)
    Stopwatch watch_;   // on options_.clock
    // FrameStats::triangles_occluded is counted: a policy judges by it.
    bool count_occluded_;
    FrameStats stats_;
};

}  // namespace

OwnTraversal *own_traversal(Culler &culler)
{
    return dynamic_cast<OwnTraversal *>(&culler);
}

bool orders_frame(const Culler &culler)
{
    return dynamic_cast<const OwnTraversal *>(&culler) != nullptr;
}

FrameStats render_hierarchy(const SceneRenderer &renderer, const Hierarchy &hierarchy, Culler &culler,
                            const Frame &frame, const TraversalOptions &options)
{
    return FrameTraversal(renderer, hierarchy, culler, frame, options).run();
}

}  // namespace occu
