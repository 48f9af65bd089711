// SPDX-License-Identifier: MIT
// The traversal's policies across frames, each an object the traversal
// calls (traversal/traversal.h), with its own settings and state, kept per
// strategy and hierarchy. They only decide where occlusion tests are worth
// their cost; none changes a pixel, so a conservative strategy stays
// conservative under them. The programs give a strategy those its family
// wants (culling/registry.h: TraversalWants).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "spatial/hierarchy.h"
#include "traversal/frame_stats.h"

namespace occu {

// Whether a frame tests occlusion: in full, as a probe of the switch-off
// (its tests only decide whether testing resumes; the culler sees
// Frame::probe), or not at all (view-frustum culling only). Of the
// policies' answers the least holds.
enum class FrameTesting { off, probe, full };

// How the traversal takes one node of a testing frame. Of the policies'
// answers the last in this order holds.
enum class NodeTesting {
    test,              // its occlusion is tested
    // Drawn or opened without a test where it lies in the frustum; where it
    // does not, tested (the culler culls it to the frustum).
    assumed_visible,
    // Not tested: the traversal culls it to the frustum, draws or opens it.
    skipped,
};

// What a policy may know of a frame before it begins.
struct FrameOutlook {
    const std::vector<HierarchyNode> &nodes;   // the hierarchy's
    // The triangles view-frustum culling would draw (the leaves not wholly
    // outside the frustum), counted when called: a walk of the nodes
    // crossing the frustum's planes.
    std::function<std::uint64_t()> frustum_triangles;
};

class TraversalPolicy {
public:
    virtual ~TraversalPolicy() = default;
    // A frame begins.
    virtual FrameTesting begin_frame(const FrameOutlook &frame) = 0;
    // `node` comes off the front of a frame that tests as `frame`.
    virtual NodeTesting node_testing(std::uint32_t node, bool leaf, FrameTesting frame) const = 0;
    // `node` was found visible (tested or not) in a frame of the common traversal.
    virtual void visible(std::uint32_t node) { (void)node; }
    // A test found `node` occluded.
    virtual void occluded(std::uint32_t node) { (void)node; }
    // After each batch of tests: whether the frame stops testing here.
    virtual bool stop_testing(const FrameStats &so_far) { (void)so_far; return false; }
    // The frame ended, having done `stats`.
    virtual void end_frame(const FrameStats &stats) = 0;
    // Whether it reads FrameStats::triangles_occluded, which the traversal
    // counts only for a policy that does (a total over the subtree of every
    // occluded node, classified against the frustum where it crosses it).
    virtual bool reads_triangles_occluded() const { return false; }
};

// Temporal coherence: Greene et al.'s visible node list, as Moeller and
// Haines describe it ("Hierarchical Z-Buffering"): nodes that were visible
// in the previous frame are taken as visible again without an occlusion
// test, except every `retest_period` frames (staggered by node), so that
// nodes which became hidden are found. Drawing a hidden node is only
// wasted work, and it removes the test cost where little is hidden.
// Probes test without it: they judge what tests find.
class VisibleNodeList final : public TraversalPolicy {
public:
    explicit VisibleNodeList(std::uint32_t retest_period = 8) : retest_period_(retest_period ? retest_period : 1) {}
    FrameTesting begin_frame(const FrameOutlook &frame) override;
    NodeTesting node_testing(std::uint32_t node, bool leaf, FrameTesting frame) const override;
    void visible(std::uint32_t node) override { now_[node] = 1; }
    void end_frame(const FrameStats &stats) override;

private:
    std::uint32_t retest_period_;
    std::uint32_t frame_ = 0;
    std::vector<std::uint8_t> last_, now_;
};

// Adaptive switch-off (Bartz et al. 1998, section 5; Poon and Wang lost
// 30% on their open route without one): when occlusion tests culled fewer
// than `min_gain` of the triangles drawn in the frames lately tested, the
// next frames test no occlusion (view-frustum culling only) except probe
// frames, whose result can switch the tests back on. Each tested frame
// weighs by its triangles, and what the frames before it gained or lost
// is carried, halved each frame (`carried`): a view of a wall close by,
// which hides nothing and costs little either way, does not switch off
// the tests that culled most of the views before it (a level's spawn
// points: oa_minia, docs/no-occlusion.md), while frames that keep hiding
// less than the share switch them off within a few frames. A probe is
// judged alone, by what it saw up to its cut. The first probe comes
// `probe_period` frames after switching off; each probe that finds the
// tests still not worth it doubles the wait, up to `max_probe_period`;
// a view much larger than any judged since the tests went off is probed
// at once (`unjudged_view`), outside that schedule. A probe stops testing after `probe_nodes`
// node tests and judges by what it saw until then: an unbounded probe of
// an open view costs several frames' worth, and a dense view shows its
// gain sooner.
//
// Only the work the scene calls for (issue 18, item 6): a probe tests the
// inner nodes, and of the leaves only those some test found hidden (the
// leaf's own, or an inner node's above it: its children take its mark
// when a probe or a frame finds it visible); the others it draws
// untested. Where nothing is hidden (the field, scene/field.h) a tested
// frame of a strategy that waits for its answers costs two to four frames
// of view-frustum culling, most of it in the tests of leaves, and no test
// ever finds a leaf hidden there: a probe makes 420-490 tests instead of
// 1033. Where much is hidden, part goes as whole subtrees, which a probe
// of inner nodes sees (Moeller and Haines, "Hierarchical Z-Buffering": in
// Greene's scene more than 99% of the on-screen polygons lie in occluded
// octree nodes; Bartz et al. 1998, section 3, test each subdivision
// entity before what it holds); but a level's hierarchy has few inner
// nodes wholly hidden (ou-shared on pul1ctf: probes of inner nodes cull
// 88 of 378 occluded leaves where a frame culls 253), and there the
// leaves once hidden are most of what a frame culls. The marks stay: a
// leaf hidden from one spawn point is hidden from many (a level's far
// rooms), and clearing a leaf's mark where a test found it visible
// left ou-shared culling 45% of pul1ctf's occluded leaves against 70%
// (docs/real-scenes.md). The first
// frame is not a probe: a first frame of inner nodes only switched shadow
// and planes off on the street route, where they cull 71% of what is
// hidden. A strategy that orders its frame itself probes through the
// common traversal (Culler::test): its own traversal cannot be cut.
class SwitchOff final : public TraversalPolicy {
public:
    struct Settings {
        double min_gain = 0.5;                 // 0: never switch off
        std::uint32_t probe_period = 8;
        std::uint32_t max_probe_period = 64;
        std::uint32_t probe_nodes = 1024;
    };
    SwitchOff() = default;
    explicit SwitchOff(const Settings &settings) : settings_(settings) {}

    FrameTesting begin_frame(const FrameOutlook &frame) override;
    // In a probe, leaves no test found hidden are drawn untested.
    NodeTesting node_testing(std::uint32_t node, bool leaf, FrameTesting frame) const override;
    // A marked inner node found visible in a testing frame passes its mark
    // to its children (they were hidden with it).
    void visible(std::uint32_t node) override;
    void occluded(std::uint32_t node) override;
    // A probe stops once its node tests used up its budget, and judges by
    // what it saw until then.
    bool stop_testing(const FrameStats &so_far) override;
    // Judged by the frame's triangles drawn and triangles in the subtrees
    // found occluded, as far as the frame tested (for a cut probe, up to
    // the cut), with the balance carried from the frames before (none
    // into a probe).
    void end_frame(const FrameStats &stats) override;
    bool reads_triangles_occluded() const override { return true; }
    bool off() const { return off_; }

private:
    // Whether this frame's tests tell what they found (none after a cut).
    bool testing() const { return (!off_ || probe_) && !cut_; }

    Settings settings_;
    // The share of the balance (triangles occluded less min_gain times
    // those drawn) of the frames before that the next tested frame adds to.
    static constexpr double carried = 0.5;
    // A switched-off frame whose frustum holds more than this many times
    // the largest view judged is probed at once: what was judged says
    // nothing of a view that much larger (a level's spawn route: views of
    // a wall close by, 300-2,400 triangles, then a room of 37,000 whose
    // tests cull 97%). Routes where the tests never pay stay within it:
    // the field's views within 1.28x of the least, the city's open route
    // 1.06x.
    static constexpr double unjudged_view = 2.0;
    const std::vector<HierarchyNode> *nodes_ = nullptr;
    // Per node: some test found it (or an inner node above it) hidden.
    std::vector<std::uint8_t> hidden_;
    bool off_ = false, probe_ = false;
    bool scheduled_probe_ = false;       // this probe is the wait's, not a larger view's
    double balance_ = 0.0;               // of the frames tested since the tests came on
    bool cut_ = false;                   // this probe stopped testing
    std::uint64_t judged_triangles_ = 0, judged_occluded_ = 0;   // at the cut
    std::uint32_t wait_ = 0;             // frames between probes now
    std::uint32_t frames_to_probe_ = 0;
    // The largest view (triangles in the frustum) judged not worth testing
    // since the tests went off: the frame that switched them off and the
    // probes since.
    std::uint64_t judged_view_triangles_ = 0;
};

}  // namespace occu
