// The traversal's two policies across frames, each its own settings and
// state, kept per strategy and hierarchy. Both only decide where occlusion
// tests are worth their cost; neither changes a pixel, so a conservative
// strategy stays conservative under them. The walkthrough applies them to
// the strategies whose tests query the rasterizer (culling/registry.h).
#pragma once

#include <cstdint>
#include <vector>

namespace occu {

// Temporal coherence: Greene et al.'s visible node list, as Moeller and
// Haines describe it ("Hierarchical Z-Buffering"): nodes that were visible
// in the previous frame are taken as visible again without an occlusion
// test, except every `retest_period` frames (staggered by node), so that
// nodes which became hidden are found. Drawing a hidden node is only
// wasted work, and it removes the test cost where little is hidden.
class VisibleNodeList {
public:
    explicit VisibleNodeList(std::uint32_t retest_period = 8) : retest_period_(retest_period ? retest_period : 1) {}
    void begin_frame(std::size_t nodes);
    // Taken as visible without a test this frame.
    bool assumed_visible(std::uint32_t node) const
    {
        return last_[node] && (frame_ + node) % retest_period_ != 0;
    }
    void mark_visible(std::uint32_t node) { now_[node] = 1; }
    void end_frame();

private:
    std::uint32_t retest_period_;
    std::uint32_t frame_ = 0;
    std::vector<std::uint8_t> last_, now_;
};

// Adaptive switch-off (Bartz et al. 1998, section 5; Poon and Wang lost
// 30% on their open route without one): when occlusion tests culled fewer
// than `min_gain` of the triangles drawn in a frame, the next frames test
// no occlusion (view-frustum culling only) except probe frames, whose
// result can switch the tests back on. The first probe comes
// `probe_period` frames after switching off; each probe that finds the
// tests still not worth it doubles the wait, up to `max_probe_period`.
// A probe stops testing after `probe_nodes` node tests and judges by what
// it saw until then: an unbounded probe of an open view costs several
// frames' worth, and a dense view shows its gain sooner.
//
// Only the work the scene calls for (issue 18, item 6): a probe tests inner
// nodes only and draws leaves untested (`probe_leaves` off). Where nothing
// is hidden (the field, scene/field.h) a tested frame of a strategy that
// waits for its answers costs two to four frames of view-frustum culling,
// most of it in the tests of leaves; where much is hidden, most of it goes
// as whole subtrees, which a probe of inner nodes sees (Moeller and Haines,
// "Hierarchical Z-Buffering": in Greene's scene more than 99% of the
// on-screen polygons lie in occluded octree nodes; Bartz et al. 1998,
// section 3, test each subdivision entity before what it holds). On the field a probe then makes 420-490 tests instead of
// 1033 and costs a third of what it did; on the city's routes the
// strategies draw what they drew (docs/no-occlusion.md). The first frame
// is not a probe: a first frame of inner nodes only switched shadow and
// planes off on the street route, where they cull 71% of what is hidden.
// A strategy that orders its frame itself probes through the common
// traversal (Culler::test): its own traversal cannot be cut.
class SwitchOff {
public:
    struct Settings {
        double min_gain = 0.5;                 // 0: never switch off
        std::uint32_t probe_period = 8;
        std::uint32_t max_probe_period = 64;
        std::uint32_t probe_nodes = 1024;
        bool probe_leaves = false;             // probes test leaves too
    };
    SwitchOff() = default;
    explicit SwitchOff(const Settings &settings) : settings_(settings) {}

    // Whether this frame tests occlusion (also true for a probe frame).
    bool begin_frame();
    bool probing() const { return probe_; }
    // In a probe: whether leaves are drawn untested.
    bool probe_skips_leaves() const { return probe_ && !settings_.probe_leaves; }
    // In a probe: whether the node tests so far used up its budget.
    bool probe_spent(std::uint32_t nodes_tested) const { return probe_ && nodes_tested >= settings_.probe_nodes; }
    // The frame's triangles drawn and triangles in the subtrees found
    // occluded, as far as the frame tested (for a cut probe, up to the cut).
    void end_frame(bool tested, double triangles_drawn, double triangles_occluded);
    bool off() const { return off_; }

private:
    Settings settings_;
    bool off_ = false, probe_ = false;
    std::uint32_t wait_ = 0;             // frames between probes now
    std::uint32_t frames_to_probe_ = 0;
};

}  // namespace occu
