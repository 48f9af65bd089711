// SPDX-License-Identifier: MIT
#include "strategies/bittner_coherent_hierarchical_culling/family.h"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <queue>
#include <random>
#include <stdexcept>

#include "culling/occlusion_question.h"
#include "spatial/hierarchy.h"
#include "strategies/bittner_coherent_hierarchical_culling/occlusion_unit_async_culler.h"
#include "traversal/traversal.h"

namespace occu::strategies {

namespace {

float distance_to(const Aabb &box, const glm::vec3 &p)
{
    const glm::vec3 d = glm::max(glm::max(box.min - p, p - box.max), glm::vec3(0.0f));
    return glm::length(d);
}

// One node in a batch. `retest`: a previously visible leaf, already drawn
// this frame, whose result only classifies it for the next frame.
// `conditional`: a previously invisible leaf drawn under the condition of
// its test right after the batch was issued (the GL decides); its result,
// too, only classifies it for the next frame (and pulls it up).
struct Query {
    std::uint32_t node;
    bool retest;
    AsyncTest test;
    bool conditional = false;
};

struct InFlight {
    AsyncCuller::Batch batch = 0;
    std::vector<Query> queries;   // test k is queries[k]
    std::int64_t frame = 0;       // the frame it was issued in
    // Some result decides this frame's drawing (an inner node to open or
    // cull, a leaf drawn only once found visible): read before the frame
    // ends. Otherwise the batch may be carried over and read at the start of
    // the next frame.
    bool needed = false;
};

// The strategy: CHC++'s traversal over an asynchronous culler (the
// Occlusion Unit's passes). As a Culler it answers the callers that test
// nodes themselves (the switch-off's probes) and tells the common
// traversal that it walks the hierarchy itself (OwnTraversal).
class CoherentHierarchicalCuller final : public Culler, public OwnTraversal {
public:
    CoherentHierarchicalCuller(const StrategyContext &context, const Settings &settings)
        : async_(make_occlusion_unit_async_culler(settings)), nodes_(context.hierarchy.nodes()),
          period_(std::uint32_t(settings.integer("period"))), max_bounds_(std::size_t(settings.integer("bounds"))),
          max_test_area_(settings.number("max-test-area")), tiles_per_pass_(async_->batch_capacity()),
          conditional_(settings.text("conditional") == "off"      ? Conditional::off
                       : settings.text("conditional") == "always" ? Conditional::always
                                                                  : Conditional::waits),
          poll_every_(std::uint32_t(settings.integer("poll")))
    {
        parent_.assign(nodes_.size(), none);
        for (std::uint32_t n = 0; n < nodes_.size(); ++n)
            for (std::uint32_t c = 0; c < nodes_[n].child_count; ++c)
                parent_[nodes_[n].first_child + c] = n;
        // CHC++'s random offsets: each node's re-tests fall on its own
        // frames, so that they spread instead of coming all in one frame.
        std::mt19937 random(2008);
        std::uniform_int_distribution<std::uint32_t> offset(0, period_ - 1);
        offset_.resize(nodes_.size());
        for (std::uint32_t &o : offset_)
            o = offset(random);
        visible_frame_.assign(nodes_.size(), -2);
    }

    void begin_frame(const Frame &frame) override
    {
        frame_.emplace(frame);
        async_->begin_frame(frame);
        ++frame_number_;
        // The passes the previous frame did not wait for: their results
        // classify nodes for this frame (they were tested against that
        // frame's depth, after everything drawn before them: a node found
        // visible there is drawn untested here, one found hidden is tested
        // here). Its rasterizer has long finished them.
        std::deque<InFlight> carried;
        carried.swap(flight_);
        for (InFlight &f : carried)
            handle(f);
        // Pull-up makes the root visible in every frame that saw anything.
        history_ = was_visible(0);
    }

    // Callers that test nodes themselves get plain answers: one batch per
    // group of tests, read at once, no temporal coherence.
    void test(std::vector<NodeTest> &tests) override
    {
        std::vector<std::pair<std::size_t, Query>> pending;
        for (std::size_t i = 0; i < tests.size(); ++i) {
            NodeTest &t = tests[i];
            t.result = Visibility::visible;
            if (frame_->frustum.classify(t.box) == Frustum::Side::outside) {
                t.result = Visibility::view_culled;
                continue;
            }
            AsyncTest a;
            if (prepare(t.node, a))
                pending.push_back({i, Query{t.node, false, std::move(a)}});
        }
        std::vector<PixelRect> rects;
        std::vector<std::size_t> members;
        for (std::size_t k = 0; k < pending.size(); ++k) {
            rects.push_back(pending[k].second.test.area);
            members.push_back(k);
        }
        for (const std::vector<std::size_t> &group :
             disjoint_groups(rects, members, tiles_per_pass_, async_->shares_overlapping())) {
            std::vector<AsyncTest> batch;
            for (std::size_t k : group)
                batch.push_back(pending[k].second.test);
            const AsyncCuller::Batch b = async_->issue(std::move(batch));
            for (std::size_t j = 0; j < group.size(); ++j)
                tests[pending[group[j]].first].result = async_->answer(b, j);
            async_->release(b);
        }
    }

    // CHC++'s traversal: the distance queue, the queue of passes in flight
    // (results handled in the order issued, each as soon as it is
    // available), the batch of previously invisible nodes (i-queue) and the
    // re-tests of previously visible leaves (v-queue).
    void traverse(FrameSink &sink) override
    {
        sink_ = &sink;
        push(0);
        for (;;) {
            // Results that are ready, or that the traversal has to wait for
            // because nothing else is left to do.
            // Passes end in order and the rasterizer finishes them in
            // order, so the front one is asked first.
            // While there is traversal to do, only every poll_every_-th
            // step asks (0: none). Asking costs little in itself, but a GL
            // may take a question asked with nothing drawn since the last
            // as a wait and start rendering the pass at once (llvmpipe then
            // ends the scene being binned: spec MESAX_occlusion_unit_async,
            // issue 19), and steps that open inner nodes draw nothing.
            const bool walk = walks_on();
            const bool busy = walk || issues();
            const bool ask = !busy || (poll_every_ > 0 && ++steps_ % poll_every_ == 0);
            while (ask && !flight_.empty()) {
                auto next = flight_.begin();
                if (!async_->ready(next->batch)) {
                    if (walk || issues())
                        break;   // traverse (or issue the batch) first
                    if (!vqueue_.empty()) {
                        issue_batch();   // fill the wait with re-tests
                        continue;
                    }
                    // Nothing to do but wait: leaves whose results are all
                    // that is left go to the GL under conditions instead
                    // (not in a frame without history: its culled leaves
                    // are what the next frame's coherence starts from).
                    if (history_ && conditional_ == Conditional::waits &&
                        std::none_of(flight_.begin(), flight_.end(), [&](const InFlight &f) { return opens_nodes(f); }))
                        for (InFlight &f : flight_)
                            draw_conditionally(f);
                    // Wait only for a result this frame needs; the others
                    // are carried over to the next frame's start.
                    next = std::find_if(flight_.begin(), flight_.end(), [](const InFlight &f) { return f.needed; });
                    if (next == flight_.end())
                        break;
                    ++waits_;   // handle() below waits
                }
                InFlight f = std::move(*next);
                flight_.erase(next);
                handle(f);
            }
            if (walks_on()) {   // results handled above may have let it go on
                const std::uint32_t n = distance_.top().second;
                distance_.pop();
                visit(n);
                continue;
            }
            if (issues() || (flight_.empty() && !vqueue_.empty())) {
                issue_batch();
                continue;
            }
            if (std::none_of(flight_.begin(), flight_.end(), [](const InFlight &f) { return f.needed; }))
                break;
        }
        sink_ = nullptr;
    }

    CullerStats stats() const override { return async_->stats(); }
    std::string note() const override { return async_->note(); }

private:
    static constexpr std::uint32_t none = 0xFFFFFFFFu;

    bool was_visible(std::uint32_t n) const { return visible_frame_[n] == frame_number_ - 1; }

    // Whether the traversal takes the next node off the distance queue now.
    // In a frame with history it goes on while results are pending: the
    // previously visible nodes it draws meanwhile are the occluders of the
    // nodes it tests. A frame without history (the first, or the first
    // after the switch-off kept the strategy off) draws nothing untested,
    // so a test issued ahead of the results of the nodes before it would
    // find an empty depth buffer: the whole front would be tested at once
    // and found visible. There it waits as the general algorithm does
    // (Moeller and Haines, figure 2; Bartz et al. 1998, section 3: a node
    // is tested after what lies in front of it is drawn): a batch of the
    // nearest nodes, then their results, then the nodes behind them; and
    // where passes are disjoint, a node whose area overlaps one of the
    // batch's waits for that one's result (it may lie behind it).
    bool walks_on() const { return !distance_.empty() && (history_ || (iqueue_.size() < tiles_per_pass_ && may_issue())); }

    // Whether the i-queue's nodes may be tested now: in a frame without
    // history, only once the results this frame needs are in (walks_on).
    bool may_issue() const
    {
        return history_ || std::none_of(flight_.begin(), flight_.end(), [](const InFlight &f) { return f.needed; });
    }
    bool issues() const { return !iqueue_.empty() && may_issue(); }

    // Pull-up: n and its ancestors are visible in frame `frame` (this one,
    // or the previous one for a pass carried over). A node is never marked
    // with an earlier frame than it has, and an ancestor's frame is never
    // earlier than its descendants'.
    void mark_visible(std::uint32_t n) { mark_visible(n, frame_number_); }
    void mark_visible(std::uint32_t n, std::int64_t frame)
    {
        for (; n != none && visible_frame_[n] < frame; n = parent_[n])
            visible_frame_[n] = frame;
    }

    bool retest_due(std::uint32_t n) const
    {
        return (std::uint64_t(frame_number_) + offset_[n]) % period_ == 0;
    }

    void push(std::uint32_t n) { distance_.push({distance_to(nodes_[n].bounds, frame_->camera.position), n}); }

    // A visible node: drawn if a leaf, else its children join the front.
    void open(std::uint32_t n)
    {
        const HierarchyNode &node = nodes_[n];
        if (node.leaf()) {
            sink_->draw_leaf(n);
            return;
        }
        for (std::uint32_t c = 0; c < node.child_count; ++c)
            push(node.first_child + c);
    }

    void visit(std::uint32_t n)
    {
        const HierarchyNode &node = nodes_[n];
        if (frame_->frustum.classify(node.bounds) == Frustum::Side::outside) {
            sink_->cull(n, Visibility::view_culled);
            return;
        }
        AsyncTest a;
        if (was_visible(n)) {
            // Not waited for: drawn or opened now.
            if (node.leaf()) {
                sink_->draw_leaf(n);
                if (retest_due(n) && prepare(n, a))
                    vqueue_.push_back({n, true, std::move(a)});
                else
                    mark_visible(n);
            }
            else {
                open(n);   // its descendants pull it up, or it is tested as a whole next frame
            }
            return;
        }
        if (!prepare(n, a)) {
            mark_visible(n);   // untestable: visible untested
            open(n);
            return;
        }
        iqueue_.push_back({n, false, std::move(a)});
        if (iqueue_.size() >= tiles_per_pass_)
            issue_batch();
    }

    // One batch: the i-queue's nodes first, free room filled with re-tests.
    // Where the culler does not share overlapping areas (passes=disjoint) a
    // node joins only where its area overlaps none of the batch's (a tile
    // counts every proxy's fragments in it, and a visible node's proxy, a
    // re-tested leaf's above all, would keep every node under it visible);
    // the others wait for the next batch.
    void issue_batch()
    {
        std::vector<Query> queries;
        auto take = [&](std::deque<Query> &queue) {
            for (auto it = queue.begin(); it != queue.end() && queries.size() < tiles_per_pass_;) {
                const bool fits =
                    async_->shares_overlapping() || std::none_of(queries.begin(), queries.end(), [&](const Query &q) {
                        return q.test.area.overlaps(it->test.area);
                    });
                if (!fits) {
                    ++it;
                    continue;
                }
                queries.push_back(std::move(*it));
                it = queue.erase(it);
            }
        };
        take(iqueue_);
        take(vqueue_);
        if (queries.empty())
            return;
        sink_->tested(std::uint32_t(queries.size()));
        InFlight f = issue(std::move(queries));
        f.frame = frame_number_;
        f.needed = std::any_of(f.queries.begin(), f.queries.end(), [](const Query &q) { return !q.retest; });
        if (history_ && conditional_ == Conditional::always)
            draw_conditionally(f);
        flight_.push_back(std::move(f));
    }

    // Whether a pass in flight holds an inner node, whose result the
    // traversal needs to go on (to open it or cull it).
    bool opens_nodes(const InFlight &f) const
    {
        return std::any_of(f.queries.begin(), f.queries.end(),
                           [&](const Query &q) { return !q.retest && !nodes_[q.node].leaf(); });
    }

    // The previously invisible leaves of batch f drawn now, each under the
    // condition of its own test: drawn only if the test finds it visible,
    // nobody waiting for the answer (the culler culls it where it knows the
    // answer already). The batch is then needed this frame only if it holds
    // inner nodes.
    void draw_conditionally(InFlight &f)
    {
        for (std::size_t k = 0; k < f.queries.size(); ++k) {
            Query &q = f.queries[k];
            if (q.retest || q.conditional || !nodes_[q.node].leaf())
                continue;
            q.conditional = true;
            if (!async_->draw_if_visible(f.batch, k, [&] { sink_->draw_leaf_conditionally(q.node); }))
                sink_->cull(q.node, Visibility::occluded);
        }
        f.needed = opens_nodes(f);
    }

    InFlight issue(std::vector<Query> queries)
    {
        InFlight f;
        std::vector<AsyncTest> tests;
        for (const Query &q : queries)
            tests.push_back(q.test);
        f.batch = async_->issue(std::move(tests));
        f.queries = std::move(queries);
        return f;
    }

    // A batch's results. Carried over from the previous frame (sink_ null),
    // a batch holds only re-tests and conditional draws.
    void handle(InFlight &f)
    {
        for (std::size_t k = 0; k < f.queries.size(); ++k) {
            const Query &q = f.queries[k];
            const bool occluded = async_->answer(f.batch, k) == Visibility::occluded;
            if (q.conditional || q.retest) {
                if (!occluded)
                    mark_visible(q.node, f.frame);   // else hidden: tested before it is drawn next frame
                continue;
            }
            if (!sink_)
                throw std::logic_error("chc: a pass whose results the frame needed was carried over");
            if (occluded) {
                sink_->cull(q.node, Visibility::occluded);
                continue;
            }
            mark_visible(q.node);
            open(q.node);
        }
        async_->release(f.batch);
    }

    // Node n's test, or false when n is visible untested: its box has no
    // footprint, covers more than max-test-area of the viewport, or the
    // culler cannot test it. Tight bounds: the boxes of n's descendants,
    // level by level while they number at most `bounds` (those wholly
    // outside the frustum left out: nothing in them is seen); where the
    // culler cannot test those, n's own box.
    bool prepare(std::uint32_t n, AsyncTest &a) const
    {
        const Frame &f = *frame_;
        const auto footprint = f.footprint(nodes_[n].bounds);
        if (!footprint || double(footprint->rect.area()) > max_test_area_ * double(f.width) * double(f.height))
            return false;
        std::vector<std::uint32_t> cut{n};
        for (;;) {
            std::vector<std::uint32_t> deeper;
            bool opened = false;
            for (std::uint32_t m : cut) {
                const HierarchyNode &node = nodes_[m];
                if (node.leaf()) {
                    deeper.push_back(m);
                    continue;
                }
                opened = true;
                for (std::uint32_t c = 0; c < node.child_count; ++c)
                    if (f.frustum.classify(nodes_[node.first_child + c].bounds) != Frustum::Side::outside)
                        deeper.push_back(node.first_child + c);
            }
            if (!opened || deeper.empty() || deeper.size() > max_bounds_)
                break;
            cut.swap(deeper);
        }
        a.node = n;
        if (cut.size() > 1) {
            a.boxes.clear();
            for (std::uint32_t m : cut)
                a.boxes.push_back(nodes_[m].bounds);
            if (async_->prepare(a))
                return true;
        }
        a.boxes.assign(1, nodes_[n].bounds);
        return async_->prepare(a);
    }

    std::unique_ptr<AsyncCuller> async_;
    const std::vector<HierarchyNode> &nodes_;
    std::uint32_t period_;
    std::size_t max_bounds_;
    double max_test_area_;
    std::size_t tiles_per_pass_;
    // Where previously invisible leaves are drawn under conditional
    // rendering instead of once their results are read: nowhere, in place
    // of a wait (when nothing is left but results, none of them an inner
    // node's), or always, right after their pass ends.
    enum class Conditional { off, waits, always } conditional_;
    std::uint32_t poll_every_;
    std::uint64_t steps_ = 0;
    std::vector<std::uint32_t> parent_, offset_;
    std::vector<std::int64_t> visible_frame_;   // the last frame a node was visible in
    std::int64_t frame_number_ = 0;
    std::optional<Frame> frame_;
    // Something was visible in the previous frame: it is drawn untested
    // while this frame's tests are pending (walks_on).
    bool history_ = false;
    std::uint64_t waits_ = 0;   // times the traversal had nothing to do but wait for a pass

    // One frame's traversal state (traverse()).
    FrameSink *sink_ = nullptr;
    using Entry = std::pair<float, std::uint32_t>;   // distance, node
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> distance_;
    std::deque<Query> iqueue_, vqueue_;
    std::deque<InFlight> flight_;   // in flight; at a frame's end, those carried over
};

}  // namespace

StrategyFamily coherent_hierarchical_culling_family()
{
    using Role = SettingSpec::Role;
    StrategyFamily f;
    f.name = "chc";
    f.paper = "Bittner, Wimmer, Piringer and Purgathofer 2004 (CHC); Mattausch, Bittner and Wimmer 2008 (CHC++)";
    f.summary = "coherent hierarchical culling: previously visible nodes drawn without waiting, the others tested "
                "in batched multi-tile passes read when ready (GL_MESAX_occlusion_unit_async, or emulated)";
    // Its own temporal coherence and its own traversal: the walkthrough's
    // coherence (for families that query the rasterizer through the common
    // traversal) does not apply. Switch-off does (traversal/traversal.h):
    // where nothing is hidden (the field, scene/field.h) its re-tests of
    // visible nodes, every `period` frames each, and the tests of nodes
    // entering the frustum cost about a third of a frame on llvmpipe and
    // find nothing. Its answers come while drawing goes on (family.h: the
    // previously visible are drawn without waiting), so its tests pay at a
    // tenth of the gain that tests which stall must reach: on the
    // city's open route it culls 13% of the triangles vfc draws and is
    // faster than vfc (docs/coherent-hierarchical-culling.md), and stays on.
    f.traversal.switch_off = true;
    f.traversal.switch_off_share = 0.1;
    f.traversal.own_traversal = true;
    f.settings = {
        integer_setting("batch", 64, 1, 4096, Role::cost,
                        "previously invisible nodes tested together in one pass (one tile each; at most the unit's tiles)"),
        integer_setting("period", 16, 1, 1000, Role::cost,
                        "a previously visible leaf is re-tested every this many frames (from a random offset per node)", "1"),
        number_setting("tolerance", 0.0, 0.0, 0.999, Role::approximation,
                       "visibility threshold (CHC++): occluded when NOHC <= tolerance * PHC"),
        occlusion_answer_setting(),
        integer_setting("bounds", 1, 1, 64, Role::cost,
                        "tight bounds: an inner node is tested by its descendants' boxes, level by level while they are at most this many", "1"),
        choice_setting("passes", {"disjoint", "shared"},
                       "nodes share a pass only where their tiles are disjoint, or always (fewer passes, less culling)"),
        number_setting("max-test-area", 0.25, 0.0001, 1.0, Role::cost,
                       "boxes covering more of the viewport are taken as visible untested", "1"),
        choice_setting("conditional", {"waits", "always", "off"},
                       "previously invisible leaves drawn under conditional rendering on their tiles (the GL decides, "
                       "nobody waits) instead of once their results are read: in place of a wait at the end of the "
                       "traversal, always (right after their pass), or never"),
        integer_setting("poll", 1, 0, 1000, Role::cost,
                        "the oldest pass in flight is asked for its result every this many steps of the traversal "
                        "(0: only when it has nothing else to do); asking with nothing drawn in between may start "
                        "the pass on the GL (a scene of its own on llvmpipe)"),
    };
    f.presets = {{"chc-shared", "passes=shared"}};
    // The switch-off's probes through the common traversal.
    f.test_variants = {StrategyTestVariant("chc").with_probing_switch_off(), StrategyTestVariant("chc:answer=exact")};
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<CoherentHierarchicalCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
