// SPDX-License-Identifier: MIT
// The traversal: a "do not test below" answer stops occlusion tests under
// a node and still draws what vfc draws; switched-off occlusion tests come
// back only in probe frames, backing off; temporal coherence takes last
// frame's visible nodes as visible without a test.
#include "traversal/traversal.h"

#include <gtest/gtest.h>

#include <optional>
#include <set>

#include "culling/registry.h"
#include "gl/offscreen_context.h"

using namespace occu;

namespace {

// Answers visible with "do not test below" for the root, visible
// otherwise, and counts the nodes it is asked about.
class GiveUpAtTheRoot final : public Culler {
public:
    void begin_frame(const Frame &frame) override { frustum_.emplace(frame.frustum); }
    void test(std::vector<NodeTest> &tests) override
    {
        for (NodeTest &t : tests) {
            ++tested;
            t.result = frustum_->classify(t.box) == Frustum::Side::outside ? Visibility::view_culled
                                                                           : Visibility::visible;
            t.test_below = t.node != 0;
        }
    }
    std::uint32_t tested = 0;

private:
    std::optional<Frustum> frustum_;
};

// A row of `n` unit boxes along x at z = -5, one leaf each (12 triangles),
// in a 32x32 context, and a camera at z = 20 that sees part of the row.
struct BoxRow {
    explicit BoxRow(int n)
    {
        scene.meshes.emplace_back();
        for (int i = 0; i < n; ++i)
            append_box(scene.meshes[0], Aabb::of({float(i) * 3.0f, 0, -5}, {float(i) * 3.0f + 1, 1, -4}));
        scene.update_bounds();
        HierarchyOptions ho;
        ho.max_leaf_triangles = 12;
        h.emplace(Hierarchy::build(scene, ho));
        renderer.emplace(scene, *h);
        camera.position = {10, 0.5f, 20};
        camera.target = {10, 0.5f, -5};
    }
    gl::OffscreenContext ctx{32, 32};
    Scene scene;
    std::optional<Hierarchy> h;
    std::optional<SceneRenderer> renderer;
    Camera camera;
};

// A hierarchy of five nodes: the root, an inner node 1 over leaves 3
// and 4, and leaf 2.
const std::vector<HierarchyNode> &five_nodes()
{
    static const std::vector<HierarchyNode> nodes = [] {
        std::vector<HierarchyNode> n(5);
        n[0].first_child = 1;
        n[0].child_count = 2;
        n[1].first_child = 3;
        n[1].child_count = 2;
        return n;
    }();
    return nodes;
}

// A frame over five_nodes() whose frustum holds `triangles`.
FrameOutlook view_of(std::uint64_t triangles)
{
    return {five_nodes(), [triangles] { return triangles; }};
}

}  // namespace

TEST(Traversal, NoTestsBelowANodeTheCullerGaveUpOn)
{
    const BoxRow row(40);
    const Hierarchy &h = *row.h;
    ASSERT_GT(h.leaf_count(), 8u);
    GiveUpAtTheRoot give_up;
    const Strategy vfc = make_strategy("vfc", {row.scene, h, *row.renderer});
    const Frame frame(row.camera, 32, 32);
    const FrameStats s = render_hierarchy(*row.renderer, h, give_up, frame);
    const FrameStats v = render_hierarchy(*row.renderer, h, *vfc.culler, frame);
    EXPECT_EQ(s.leaves_drawn, v.leaves_drawn);
    EXPECT_GT(v.leaves_drawn, 0u);
    EXPECT_LT(v.leaves_drawn, h.leaf_count()) << "the frustum should leave some leaves out";
    // The root, then only nodes outside the frustum.
    EXPECT_EQ(give_up.tested, 1 + s.nodes_view_culled);
}

// Where occlusion tests cull nothing they stop after the first frame and
// come back only in probe frames, 8 frames later, then twice as long after
// each probe that finds them still not worth it, up to 64.
TEST(Traversal, SwitchedOffProbesBackOff)
{
    const BoxRow row(8);
    const Strategy none = make_strategy("none", {row.scene, *row.h, *row.renderer});   // never finds anything occluded
    SwitchOff switch_off;
    TraversalOptions options;
    options.policies = {&switch_off};
    const Frame frame(row.camera, 32, 32);
    std::vector<std::uint32_t> tested;
    for (std::uint32_t f = 0; f < 200; ++f)
        if (render_hierarchy(*row.renderer, *row.h, *none.culler, frame, options).occlusion_tested)
            tested.push_back(f);
    EXPECT_EQ(tested, (std::vector<std::uint32_t>{0, 8, 24, 56, 120, 184}));
}

// Counts the leaves and inner nodes it is asked about, and which frames
// were begun as probes; answers as vfc does.
class CountingCuller final : public Culler {
public:
    explicit CountingCuller(const Hierarchy &h) : h_(h) {}
    void begin_frame(const Frame &frame) override
    {
        probes += frame.probe;
        frustum_.emplace(frame.frustum);
    }
    void test(std::vector<NodeTest> &tests) override
    {
        for (NodeTest &t : tests) {
            ++(h_.nodes()[t.node].leaf() ? leaves : inner);
            t.result = frustum_->classify(t.box) == Frustum::Side::outside ? Visibility::view_culled
                                                                           : Visibility::visible;
        }
    }
    std::uint32_t leaves = 0, inner = 0, probes = 0;

private:
    const Hierarchy &h_;
    std::optional<Frustum> frustum_;
};

// A probe (traversal/policies.h) is begun as a Frame::probe and draws what
// a frame draws; where no test found a leaf hidden it tests inner nodes
// only, a frame leaves too.
TEST(Traversal, ProbesTestInnerNodesOnlyAndDrawWhatAFrameDraws)
{
    const BoxRow row(40);
    SwitchOff switch_off;   // culls nothing: off after frame 0, probe at frame 8
    TraversalOptions options;
    options.policies = {&switch_off};
    CountingCuller counting(*row.h);
    const Frame frame(row.camera, 32, 32);
    std::vector<FrameStats> stats;
    for (int f = 0; f <= 8; ++f)
        stats.push_back(render_hierarchy(*row.renderer, *row.h, counting, frame, options));
    ASSERT_TRUE(stats[8].occlusion_tested);
    EXPECT_EQ(counting.probes, 1u);
    EXPECT_EQ(stats[8].drawn, stats[0].drawn);
    EXPECT_GT(stats[0].nodes_tested, stats[8].nodes_tested);
    const std::uint32_t leaves_in_frame = counting.leaves;
    EXPECT_GT(leaves_in_frame, 0u);
    counting.leaves = 0;
    render_hierarchy(*row.renderer, *row.h, counting, frame, options);   // frame 9: off
    EXPECT_EQ(counting.leaves, 0u);
    // The leaves were tested in frame 0 only.
    CountingCuller probe_only(*row.h);
    SwitchOff fresh;
    options.policies = {&fresh};
    for (int f = 0; f <= 8; ++f) {
        if (f == 8)
            probe_only.leaves = probe_only.inner = 0;
        render_hierarchy(*row.renderer, *row.h, probe_only, frame, options);
    }
    EXPECT_EQ(probe_only.leaves, 0u) << "a probe tested leaves";
    EXPECT_GT(probe_only.inner, 0u) << "a probe tested no inner node";
}

// Finds the leaves it is given occluded and every other node in the
// frustum visible, and keeps the leaves it was asked about since cleared.
class HidesLeaves final : public Culler {
public:
    HidesLeaves(const Hierarchy &h, std::set<std::uint32_t> hidden) : h_(h), hidden_(std::move(hidden)) {}
    void begin_frame(const Frame &frame) override { frustum_.emplace(frame.frustum); }
    void test(std::vector<NodeTest> &tests) override
    {
        for (NodeTest &t : tests) {
            if (h_.nodes()[t.node].leaf())
                leaves.insert(t.node);
            t.result = frustum_->classify(t.box) == Frustum::Side::outside ? Visibility::view_culled
                       : hidden_.count(t.node)                             ? Visibility::occluded
                                                                           : Visibility::visible;
        }
    }
    std::set<std::uint32_t> leaves;

private:
    const Hierarchy &h_;
    const std::set<std::uint32_t> hidden_;
    std::optional<Frustum> frustum_;
};

// A probe tests the leaves the tests before it found hidden (too few to
// keep the tests on) and no other leaf, and culls them as a frame does.
TEST(Traversal, AProbeTestsTheLeavesFoundHidden)
{
    const BoxRow row(40);
    const Strategy vfc = make_strategy("vfc", {row.scene, *row.h, *row.renderer});
    const Frame frame(row.camera, 32, 32);
    const FrameStats v = render_hierarchy(*row.renderer, *row.h, *vfc.culler, frame);
    ASSERT_GT(v.drawn.size(), 4u);
    const std::set<std::uint32_t> hidden{v.drawn[1], v.drawn[3]};
    HidesLeaves hides(*row.h, hidden);
    SwitchOff switch_off;   // off after frame 0, probe at frame 8
    TraversalOptions options;
    options.policies = {&switch_off};
    std::vector<FrameStats> stats;
    for (int f = 0; f <= 8; ++f) {
        if (f == 8)
            hides.leaves.clear();
        stats.push_back(render_hierarchy(*row.renderer, *row.h, hides, frame, options));
    }
    ASSERT_TRUE(switch_off.off());
    ASSERT_FALSE(stats[7].occlusion_tested);
    ASSERT_TRUE(stats[8].occlusion_tested);
    EXPECT_EQ(hides.leaves, hidden);
    EXPECT_EQ(stats[8].drawn, stats[0].drawn);
    EXPECT_EQ(stats[8].drawn.size() + hidden.size(), v.drawn.size());
}

// Answers occluded for every node but the root, which it finds visible.
class HidesAllButTheRoot final : public Culler {
public:
    void begin_frame(const Frame &frame) override { frustum_.emplace(frame.frustum); }
    void test(std::vector<NodeTest> &tests) override
    {
        for (NodeTest &t : tests)
            t.result = frustum_->classify(t.box) == Frustum::Side::outside ? Visibility::view_culled
                       : t.node == 0                                       ? Visibility::visible
                                                                           : Visibility::occluded;
    }

private:
    std::optional<Frustum> frustum_;
};

// The triangles in the subtrees of occluded nodes are totalled for a
// policy that reads them (the switch-off): those of the leaves in the
// frustum, as view-frustum culling draws them; without such a policy
// nothing is totalled.
TEST(Traversal, OccludedTrianglesAreCountedOnlyForAPolicyThatReadsThem)
{
    const BoxRow row(40);
    const Hierarchy &h = *row.h;
    const Strategy vfc = make_strategy("vfc", {row.scene, h, *row.renderer});
    const Frame frame(row.camera, 32, 32);
    const FrameStats v = render_hierarchy(*row.renderer, h, *vfc.culler, frame);
    ASSERT_GT(v.triangles, 0u);
    HidesAllButTheRoot hides;
    const FrameStats plain = render_hierarchy(*row.renderer, h, hides, frame);
    EXPECT_EQ(plain.leaves_drawn, 0u);
    EXPECT_GT(plain.nodes_occluded, 0u);
    EXPECT_EQ(plain.triangles_occluded, 0u);
    SwitchOff switch_off;
    TraversalOptions options;
    options.policies = {&switch_off};
    const FrameStats judged = render_hierarchy(*row.renderer, h, hides, frame, options);
    EXPECT_EQ(judged.nodes_occluded, plain.nodes_occluded);
    EXPECT_EQ(judged.triangles_occluded, v.triangles);
    EXPECT_FALSE(switch_off.off());
}

// Nodes visible last frame are drawn untested, except every retest_period
// frames; so a second frame tests fewer nodes and draws the same.
TEST(Traversal, VisibleNodeListSkipsTestsOfLastFramesVisibleNodes)
{
    const BoxRow row(16);
    const Strategy vfc = make_strategy("vfc", {row.scene, *row.h, *row.renderer});
    VisibleNodeList coherence(1000);
    TraversalOptions options;
    options.policies = {&coherence};
    const Frame frame(row.camera, 32, 32);
    const FrameStats first = render_hierarchy(*row.renderer, *row.h, *vfc.culler, frame, options);
    const FrameStats second = render_hierarchy(*row.renderer, *row.h, *vfc.culler, frame, options);
    EXPECT_EQ(first.leaves_drawn, second.leaves_drawn);
    EXPECT_LT(second.nodes_tested, first.nodes_tested);
}

// The visible node list takes last frame's visible nodes as visible in
// frames that test in full only: a probe judges what tests find.
TEST(TraversalPolicies, VisibleNodeListAppliesToFullFramesOnly)
{
    VisibleNodeList coherence(1000);
    coherence.begin_frame(view_of(1000));
    coherence.visible(2);
    coherence.end_frame({});
    EXPECT_EQ(coherence.begin_frame(view_of(1000)), FrameTesting::full);
    EXPECT_EQ(coherence.node_testing(2, true, FrameTesting::full), NodeTesting::assumed_visible);
    EXPECT_EQ(coherence.node_testing(1, true, FrameTesting::full), NodeTesting::test);
    EXPECT_EQ(coherence.node_testing(2, true, FrameTesting::probe), NodeTesting::test);
}

// A probe skips leaves, stops once its node tests reach the budget, and is
// judged by what it had seen at that point, not by the frame's end.
TEST(TraversalPolicies, ProbeStopsAtItsBudgetAndIsJudgedThere)
{
    SwitchOff::Settings settings;
    settings.min_gain = 0.5;
    settings.probe_period = 1;
    settings.probe_nodes = 10;
    SwitchOff switch_off(settings);
    ASSERT_EQ(switch_off.begin_frame(view_of(100)), FrameTesting::full);
    FrameStats nothing_hidden;
    nothing_hidden.triangles = 100;
    switch_off.end_frame(nothing_hidden);
    ASSERT_TRUE(switch_off.off());
    ASSERT_EQ(switch_off.begin_frame(view_of(100)), FrameTesting::probe);
    EXPECT_EQ(switch_off.node_testing(3, true, FrameTesting::probe), NodeTesting::skipped);
    EXPECT_EQ(switch_off.node_testing(0, false, FrameTesting::probe), NodeTesting::test);
    FrameStats so_far;
    so_far.nodes_tested = 9;
    EXPECT_FALSE(switch_off.stop_testing(so_far));
    so_far.nodes_tested = 10;
    so_far.triangles = 100;
    so_far.triangles_occluded = 80;   // worth it, as far as it tested
    EXPECT_TRUE(switch_off.stop_testing(so_far));
    FrameStats whole = so_far;
    whole.triangles = 1000;            // drawn untested after the cut
    switch_off.end_frame(whole);
    EXPECT_FALSE(switch_off.off());
    EXPECT_EQ(switch_off.begin_frame(view_of(100)), FrameTesting::full);
}

// The switch-off judges the tested frames lately drawn, each by its
// triangles: a small view that hides nothing (a wall close by, 600
// triangles) after one whose tests culled much (3,000 of 4,000) does not
// switch the tests off for the views that follow; frames of the same size
// that keep hiding nothing do, within a few frames.
TEST(TraversalPolicies, ASmallFrameHidingNothingDoesNotOutweighTheFramesBefore)
{
    SwitchOff switch_off;   // min_gain 0.5
    ASSERT_EQ(switch_off.begin_frame(view_of(1000)), FrameTesting::full);
    FrameStats much_hidden;
    much_hidden.triangles = 1000;
    much_hidden.triangles_occluded = 3000;
    switch_off.end_frame(much_hidden);
    ASSERT_FALSE(switch_off.off());
    ASSERT_EQ(switch_off.begin_frame(view_of(1000)), FrameTesting::full);
    FrameStats small_nothing_hidden;
    small_nothing_hidden.triangles = 600;
    switch_off.end_frame(small_nothing_hidden);
    EXPECT_FALSE(switch_off.off()) << "one small frame hiding nothing switched the tests off";
    int frames = 0;
    for (; frames < 8 && !switch_off.off(); ++frames) {
        ASSERT_EQ(switch_off.begin_frame(view_of(1000)), FrameTesting::full);
        FrameStats nothing_hidden;
        nothing_hidden.triangles = 1000;
        switch_off.end_frame(nothing_hidden);
    }
    EXPECT_TRUE(switch_off.off()) << "8 frames hiding nothing left the tests on";
}

// A probe tests the leaves some test found hidden, their own or an inner
// node's above them, and draws the others untested; a leaf found hidden
// once is tested by every probe after.
TEST(TraversalPolicies, AProbeTestsTheLeavesFoundHidden)
{
    SwitchOff::Settings settings;
    settings.probe_period = settings.max_probe_period = 1;   // every frame a probe once off
    SwitchOff switch_off(settings);
    ASSERT_EQ(switch_off.begin_frame(view_of(100)), FrameTesting::full);
    switch_off.visible(0);
    switch_off.occluded(1);   // leaves 3 and 4 with it
    switch_off.visible(2);
    FrameStats little_hidden;
    little_hidden.triangles = 90;
    little_hidden.triangles_occluded = 10;
    switch_off.end_frame(little_hidden);
    ASSERT_TRUE(switch_off.off());

    ASSERT_EQ(switch_off.begin_frame(view_of(100)), FrameTesting::probe);
    EXPECT_EQ(switch_off.node_testing(1, false, FrameTesting::probe), NodeTesting::test);
    EXPECT_EQ(switch_off.node_testing(2, true, FrameTesting::probe), NodeTesting::skipped);
    EXPECT_EQ(switch_off.node_testing(3, true, FrameTesting::probe), NodeTesting::skipped);
    switch_off.visible(1);    // now visible: its leaves were hidden with it
    EXPECT_EQ(switch_off.node_testing(3, true, FrameTesting::probe), NodeTesting::test);
    EXPECT_EQ(switch_off.node_testing(4, true, FrameTesting::probe), NodeTesting::test);
    switch_off.visible(3);
    switch_off.visible(4);
    switch_off.end_frame(little_hidden);
    ASSERT_TRUE(switch_off.off());

    ASSERT_EQ(switch_off.begin_frame(view_of(100)), FrameTesting::probe);
    EXPECT_EQ(switch_off.node_testing(2, true, FrameTesting::probe), NodeTesting::skipped);
    EXPECT_EQ(switch_off.node_testing(3, true, FrameTesting::probe), NodeTesting::test);
    EXPECT_EQ(switch_off.node_testing(4, true, FrameTesting::probe), NodeTesting::test);
}

// Switched off, a frame whose frustum holds more than twice the triangles
// of every view judged since is probed at once, whatever the wait; a
// view it judged not worth testing raises the bar, and the scheduled
// probe comes when it would have.
TEST(TraversalPolicies, AViewMuchLargerThanAnyJudgedIsProbedAtOnce)
{
    SwitchOff switch_off;   // probes 8 frames after switching off
    ASSERT_EQ(switch_off.begin_frame(view_of(1000)), FrameTesting::full);
    FrameStats nothing_hidden;
    nothing_hidden.triangles = 1000;
    switch_off.end_frame(nothing_hidden);
    ASSERT_TRUE(switch_off.off());
    EXPECT_EQ(switch_off.begin_frame(view_of(2000)), FrameTesting::off);
    FrameStats untested;
    untested.occlusion_tested = false;
    switch_off.end_frame(untested);
    EXPECT_EQ(switch_off.begin_frame(view_of(2001)), FrameTesting::probe);
    nothing_hidden.triangles = 2001;
    switch_off.end_frame(nothing_hidden);
    ASSERT_TRUE(switch_off.off());
    EXPECT_EQ(switch_off.begin_frame(view_of(4002)), FrameTesting::off);
    EXPECT_EQ(switch_off.begin_frame(view_of(1000)), FrameTesting::off);
    EXPECT_EQ(switch_off.begin_frame(view_of(4003)), FrameTesting::probe);
    switch_off.end_frame(nothing_hidden);
    // Frames 1-5 above; the probe 8 frames after switching off is frame 8.
    EXPECT_EQ(switch_off.begin_frame(view_of(1000)), FrameTesting::off);
    EXPECT_EQ(switch_off.begin_frame(view_of(1000)), FrameTesting::off);
    EXPECT_EQ(switch_off.begin_frame(view_of(1000)), FrameTesting::probe);
}
