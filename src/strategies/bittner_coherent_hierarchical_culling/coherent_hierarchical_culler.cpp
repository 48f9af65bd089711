#include "strategies/bittner_coherent_hierarchical_culling/family.h"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <queue>
#include <random>
#include <stdexcept>

#include "gl/occlusion_unit.h"
#include "render/occlusion_proxy.h"
#include "spatial/hierarchy.h"
#include "strategies/bartz_occlusion_unit/family.h"

namespace occu::strategies {

namespace {

float distance_to(const Aabb &box, const glm::vec3 &p)
{
    const glm::vec3 d = glm::max(glm::max(box.min - p, p - box.max), glm::vec3(0.0f));
    return glm::length(d);
}

// What a node's test draws: proxies (its own box's, or its tight bounds')
// and the tile that counts them.
struct Probe {
    PixelRect tile;
    std::vector<Aabb> proxies;
};

// One node in a pass. `retest`: a previously visible leaf, already drawn
// this frame, whose result only classifies it for the next frame.
// `conditional`: a previously invisible leaf drawn under conditional
// rendering on its tile right after the pass ended (the GL decides); its
// result, too, only classifies it for the next frame (and pulls it up).
struct Query {
    std::uint32_t node;
    bool retest;
    Probe probe;
    bool conditional = false;
};

struct InFlight {
    std::unique_ptr<gl::AsyncOcclusionPass> pass;
    std::vector<Query> queries;   // tile k is queries[k]
    std::int64_t frame = 0;       // the frame it was issued in
    // Some result decides this frame's drawing (an inner node to open or
    // cull, a leaf drawn only once found visible): read before the frame
    // ends. Otherwise the pass may be carried over and read at the start of
    // the next frame.
    bool needed = false;
};

class CoherentHierarchicalCuller final : public Culler {
public:
    CoherentHierarchicalCuller(const StrategyContext &context, const Settings &settings)
        : nodes_(context.hierarchy.nodes()), period_(std::uint32_t(settings.integer("period"))),
          max_bounds_(std::size_t(settings.integer("bounds"))), threshold_(settings.number("tolerance")),
          max_test_area_(settings.number("max-test-area")), shared_passes_(settings.text("passes") == "shared"),
          conditional_(settings.text("conditional") == "off"      ? Conditional::off
                       : settings.text("conditional") == "always" ? Conditional::always
                                                                  : Conditional::waits)
    {
        // The unit holds at most max_tiles tiles; a batch is one pass.
        tiles_per_pass_ = std::size_t(std::clamp<long>(settings.integer("batch"), 1, std::min(unit_.max_tiles(), 64)));
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
        GLint viewport[4];
        glGetIntegerv(GL_VIEWPORT, viewport);
        origin_x_ = viewport[0];
        origin_y_ = viewport[1];
        stats_ = {};
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
    }

    // Callers that test nodes themselves get plain answers: one pass per
    // batch of tiles, read at once, no temporal coherence.
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
            Probe p;
            if (probe(t.node, p))
                pending.push_back({i, Query{t.node, false, std::move(p)}});
        }
        std::vector<PixelRect> rects;
        std::vector<std::size_t> members;
        for (std::size_t k = 0; k < pending.size(); ++k) {
            rects.push_back(pending[k].second.probe.tile);
            members.push_back(k);
        }
        for (const std::vector<std::size_t> &group : disjoint_groups(rects, members, tiles_per_pass_, shared_passes_)) {
            std::vector<Query> queries;
            for (std::size_t k : group)
                queries.push_back(pending[k].second);
            InFlight f = issue(std::move(queries));
            const std::vector<gl::OcclusionRecord> &records = f.pass->records();
            for (std::size_t j = 0; j < group.size(); ++j) {
                const gl::OcclusionRecord &r = records[j];
                tests[pending[group[j]].first].result =
                    adaptive_culling_occludes(r.nohc, r.phc, threshold_) ? Visibility::occluded : Visibility::visible;
            }
            free_.push_back(std::move(f.pass));
        }
    }

    bool orders_frame() const override { return true; }

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
            while (!flight_.empty()) {
                auto next = flight_.begin();
                if (!next->pass->available()) {
                    if (!distance_.empty() || !iqueue_.empty())
                        break;   // traverse (or issue the batch) first
                    if (!vqueue_.empty()) {
                        issue_batch();   // fill the wait with re-tests
                        continue;
                    }
                    // Nothing to do but wait: leaves whose results are all
                    // that is left go to the GL under conditions instead.
                    if (conditional_ == Conditional::waits && std::none_of(flight_.begin(), flight_.end(), [&](const InFlight &f) {
                            return opens_nodes(f);
                        }))
                        for (InFlight &f : flight_)
                            draw_conditionally(f);
                    // Wait only for a result this frame needs; the others
                    // are carried over to the next frame's start.
                    next = std::find_if(flight_.begin(), flight_.end(), [](const InFlight &f) { return f.needed; });
                    if (next == flight_.end())
                        break;
                    ++waits_;   // records() below waits
                }
                InFlight f = std::move(*next);
                flight_.erase(next);
                handle(f);
            }
            if (!distance_.empty()) {
                const std::uint32_t n = distance_.top().second;
                distance_.pop();
                visit(n);
                continue;
            }
            if (!iqueue_.empty() || (flight_.empty() && !vqueue_.empty())) {
                issue_batch();
                continue;
            }
            if (std::none_of(flight_.begin(), flight_.end(), [](const InFlight &f) { return f.needed; }))
                break;
        }
        sink_ = nullptr;
    }

    CullerStats stats() const override { return stats_; }

    std::string note() const override
    {
        if (unit_.native_async())
            return {};
        return "chc: GL_MESAX_occlusion_unit_async is absent, so its passes are emulated on glRenderMode and each "
               "waits for the rasterizer at its end, as ou's do";
    }

private:
    static constexpr std::uint32_t none = 0xFFFFFFFFu;

    bool was_visible(std::uint32_t n) const { return visible_frame_[n] == frame_number_ - 1; }

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
        Probe p;
        if (was_visible(n)) {
            // Not waited for: drawn or opened now.
            if (node.leaf()) {
                sink_->draw_leaf(n);
                if (retest_due(n) && probe(n, p))
                    vqueue_.push_back({n, true, std::move(p)});
                else
                    mark_visible(n);
            }
            else {
                open(n);   // its descendants pull it up, or it is tested as a whole next frame
            }
            return;
        }
        if (!probe(n, p)) {
            mark_visible(n);   // untestable: visible untested
            open(n);
            return;
        }
        iqueue_.push_back({n, false, std::move(p)});
        if (iqueue_.size() >= tiles_per_pass_)
            issue_batch();
    }

    // One pass: the i-queue's nodes first, free tiles filled with re-tests.
    // With passes=disjoint a node joins only where its tile overlaps none of
    // the pass's (a tile counts every proxy's fragments in it, and a
    // visible node's proxy, a re-tested leaf's above all, would keep every
    // node under it visible); the others wait for the next pass.
    void issue_batch()
    {
        std::vector<Query> queries;
        auto take = [&](std::deque<Query> &queue) {
            for (auto it = queue.begin(); it != queue.end() && queries.size() < tiles_per_pass_;) {
                const bool fits = shared_passes_ || std::none_of(queries.begin(), queries.end(), [&](const Query &q) {
                                      return q.probe.tile.overlaps(it->probe.tile);
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
        if (conditional_ == Conditional::always)
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

    // The previously invisible leaves of pass f drawn now, each under
    // conditional rendering on its own tile: the GL draws it only if the
    // pass found it visible (GL_QUERY_WAIT: llvmpipe bins the draw with the
    // predicate and its rasterizer decides once the pass is done; the CPU
    // does not wait). Emulated, the records are there and the CPU decides
    // (draws() false: culled as the records say). The pass is then needed
    // this frame only if it holds inner nodes.
    void draw_conditionally(InFlight &f)
    {
        for (std::size_t k = 0; k < f.queries.size(); ++k) {
            Query &q = f.queries[k];
            if (q.retest || q.conditional || !nodes_[q.node].leaf())
                continue;
            q.conditional = true;
            gl::ConditionalTileRender c(*f.pass, k, 0, float(threshold_), true);
            if (c.draws())
                sink_->draw_leaf_conditionally(q.node);
            else
                sink_->cull(q.node, Visibility::occluded);
        }
        f.needed = opens_nodes(f);
    }

    InFlight issue(std::vector<Query> queries)
    {
        InFlight f;
        if (free_.empty())
            free_.push_back(std::make_unique<gl::AsyncOcclusionPass>(unit_));
        f.pass = std::move(free_.back());
        free_.pop_back();
        std::vector<PixelRect> tiles;
        for (const Query &q : queries) {
            const PixelRect &r = q.probe.tile;
            tiles.push_back({r.x0 + origin_x_, r.y0 + origin_y_, r.x1 + origin_x_, r.y1 + origin_y_});
        }
        {
            const ProxyTestState proxy_state;   // render/occlusion_proxy.h
            f.pass->begin(gl::OcclusionMode::brief, tiles);
            for (const Query &q : queries)
                for (const Aabb &proxy : q.probe.proxies)
                    draw_proxy_box(proxy);
            f.pass->end();
        }
        ++stats_.passes;
        f.queries = std::move(queries);
        return f;
    }

    // A pass's results. Carried over from the previous frame (sink_ null),
    // a pass holds only re-tests and conditional draws.
    void handle(InFlight &f)
    {
        const std::vector<gl::OcclusionRecord> &records = f.pass->records();
        for (std::size_t k = 0; k < f.queries.size(); ++k) {
            const Query &q = f.queries[k];
            if (q.conditional) {
                // The GL's decision, made again on the record.
                if (gl::ConditionalTileRender::passes(records[k], 0, float(threshold_)))
                    mark_visible(q.node, f.frame);
                continue;
            }
            const bool occluded = adaptive_culling_occludes(records[k].nohc, records[k].phc, threshold_);
            if (q.retest) {
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
        free_.push_back(std::move(f.pass));
    }

    // What testing node n draws, or false when n is visible untested: its
    // box has no footprint, no proxy, or covers more than max-test-area of
    // the viewport. Tight bounds: the boxes of n's descendants, level by
    // level while they number at most `bounds` (those wholly outside the
    // frustum left out: nothing in them is seen); the tile is the union of
    // their footprints.
    bool probe(std::uint32_t n, Probe &p) const
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
        if (cut.size() > 1 && bounds_for(cut, p))
            return true;
        // The node's own box.
        const auto proxy = proxy_box(nodes_[n].bounds, f.camera, f.view_projection, f.height);
        if (!proxy)
            return false;
        p.proxies.assign(1, *proxy);
        p.tile = footprint->rect;
        return true;
    }

    // The proxies and tile of the boxes of `cut`; false when one of them
    // has no footprint or proxy (the node's own box serves then).
    bool bounds_for(const std::vector<std::uint32_t> &cut, Probe &p) const
    {
        const Frame &f = *frame_;
        p.proxies.clear();
        std::optional<PixelRect> tile;
        for (std::uint32_t m : cut) {
            const auto footprint = f.footprint(nodes_[m].bounds);
            const auto proxy = proxy_box(nodes_[m].bounds, f.camera, f.view_projection, f.height);
            if (!footprint || !proxy)
                return false;
            p.proxies.push_back(*proxy);
            const PixelRect &r = footprint->rect;
            if (r.empty())
                continue;
            tile = tile ? PixelRect{std::min(tile->x0, r.x0), std::min(tile->y0, r.y0), std::max(tile->x1, r.x1),
                                    std::max(tile->y1, r.y1)}
                        : r;
        }
        p.tile = tile.value_or(PixelRect{});
        return true;
    }

    gl::OcclusionUnit unit_;
    const std::vector<HierarchyNode> &nodes_;
    std::uint32_t period_;
    std::size_t max_bounds_;
    double threshold_, max_test_area_;
    bool shared_passes_;
    // Where previously invisible leaves are drawn under conditional
    // rendering instead of once their results are read: nowhere, in place
    // of a wait (when nothing is left but results, none of them an inner
    // node's), or always, right after their pass ends.
    enum class Conditional { off, waits, always } conditional_;
    std::size_t tiles_per_pass_ = 64;
    std::vector<std::uint32_t> parent_, offset_;
    std::vector<std::int64_t> visible_frame_;   // the last frame a node was visible in
    std::int64_t frame_number_ = 0;
    std::optional<Frame> frame_;
    GLint origin_x_ = 0, origin_y_ = 0;
    CullerStats stats_;
    std::uint64_t waits_ = 0;   // times the traversal had nothing to do but wait for a pass

    // One frame's traversal state (traverse()).
    FrameSink *sink_ = nullptr;
    using Entry = std::pair<float, std::uint32_t>;   // distance, node
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> distance_;
    std::deque<Query> iqueue_, vqueue_;
    std::deque<InFlight> flight_;   // in flight; at a frame's end, those carried over
    std::vector<std::unique_ptr<gl::AsyncOcclusionPass>> free_;   // pass objects to reuse
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
    f.settings = {
        integer_setting("batch", 64, 1, 64, Role::cost,
                        "previously invisible nodes tested together in one pass (one tile each; at most the unit's tiles)"),
        integer_setting("period", 16, 1, 1000, Role::cost,
                        "a previously visible leaf is re-tested every this many frames (from a random offset per node)", "1"),
        number_setting("tolerance", 0.0, 0.0, 0.999, Role::approximation,
                       "visibility threshold (CHC++): occluded when NOHC <= tolerance * PHC"),
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
    };
    f.presets = {{"chc-shared", "passes=shared"}};
    f.make = [](const StrategyContext &context, const Settings &settings) -> std::unique_ptr<Culler> {
        return std::make_unique<CoherentHierarchicalCuller>(context, settings);
    };
    return f;
}

}  // namespace occu::strategies
