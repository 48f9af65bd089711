// SPDX-License-Identifier: MIT
// chc's own behaviour across frames (strategies/bittner_coherent_hierarchical_culling):
// a leaf hidden in one frame and seen in the next is drawn in the next
// (nodes invisible last frame are tested every frame), and a leaf that
// stays visible is re-tested once every `period` frames, not every frame
// (its ancestors stay visible through pull-up and are not tested either).
// With conditional=waits (the default) or always, a previously invisible
// leaf is drawn under conditional rendering on its tile, and the GL, not the CPU, decides
// whether it is drawn: a hidden one draws nothing, a visible one is drawn.
// Its frames against unculled ones on routes and hard cases: the
// registry-wide tests (conservative_frames_test.cpp, hard_cases_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "gl/occlusion_unit.h"

#include "culling/registry.h"
#include "evaluation/lost_pixels.h"
#include "evaluation/measurement_session.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "scene/scene.h"
#include "traversal/traversal.h"

#include "strategy_variants.h"

using namespace occu;
using namespace occu::integration;

namespace {

// A wall at z = -5 (x, y in [-3, 3]) and behind it, at z = -15, a cluster of
// small boxes around the origin: from (0, 0, 0) the wall hides them all;
// from (12, 0, 0), looking at them, they are in plain view beside the wall.
// Leaves of at most 12 triangles (a box's, or part of one).
HierarchyOptions leaves_of_12_triangles()
{
    HierarchyOptions options;
    options.max_leaf_triangles = 12;
    return options;
}

Scene wall_and_cluster()
{
    Scene scene;
    scene.meshes.emplace_back();
    append_box(scene.meshes[0], Aabb::of({-3, -3, -5.5f}, {3, 3, -5}));
    for (int i = 0; i < 4; ++i)
        append_box(scene.meshes[0],
                   Aabb::of({float(i) * 0.6f - 1.2f, -0.25f, -15.25f}, {float(i) * 0.6f - 0.8f, 0.25f, -14.75f}));
    scene.update_bounds();
    return scene;
}

struct WallAndCluster {
    WallAndCluster()
    {
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_CULL_FACE);
        glClearColor(0, 0, 0, 0);
    }
    // The leaves behind the wall.
    std::vector<std::uint32_t> cluster_leaves() const
    {
        const Hierarchy &h = setup.hierarchy();
        std::vector<std::uint32_t> leaves;
        for (std::uint32_t n = 0; n < h.nodes().size(); ++n)
            if (h.nodes()[n].leaf() && h.nodes()[n].bounds.max.z < -10.0f)
                leaves.push_back(n);
        return leaves;
    }
    gl::OffscreenContext ctx{64, 64};   // first: the renderer needs it current
    SceneSetup setup{wall_and_cluster(), leaves_of_12_triangles()};
    SceneRenderer renderer{setup.scene(), setup.hierarchy()};
};

Camera looking(glm::vec3 from, glm::vec3 at)
{
    Camera c;
    c.position = from;
    c.target = at;
    return c;
}

bool drew(const StrategyFrame &f, std::uint32_t leaf)
{
    return std::find(f.stats.drawn.begin(), f.stats.drawn.end(), leaf) != f.stats.drawn.end();
}

}  // namespace

// conditional=off: the CPU reads each result before it draws, so a hidden
// leaf is not drawn at all (otherwise it is issued under a condition that
// the GL finds false: the next test).
TEST(CoherentHierarchicalCulling, ALeafHiddenLastFrameIsDrawnInTheFrameItComesIntoView)
{
    WallAndCluster s;
    const std::vector<std::uint32_t> cluster = s.cluster_leaves();
    ASSERT_FALSE(cluster.empty());
    // period=1: visible leaves are re-tested every frame, so that a
    // cluster leaf found visible in one frame (drawn untested in the next)
    // is found hidden again by the third frame on.
    // poll=0: results are asked for only when the traversal has nothing
    // else to do; the frames must be the same.
    MeasurementSession session(s.setup, s.ctx, checking_session_options());
    for (const char *poll : {"1", "0"})
        add_variant(session, StrategyTestVariant("chc:max-test-area=1:period=1:conditional=off:poll=" + std::string(poll)));

    // Hidden for a few frames, so that nothing of the cluster is visible
    // in the frame before it comes into view; then in view beside the
    // wall; then back behind it, where the cluster, visible last frame, is
    // drawn untested (or re-tested). Every frame is the unculled one.
    const Camera behind = looking({0, 0, 0}, {0, 0, -15}), beside = looking({12, 0, 0}, {0, 0, -15});
    const std::vector<Camera> cameras = {behind, behind, behind, behind, beside, behind};
    session.walk(cameras, "chc", [&](const SessionStrategy &chc, const StrategyFrame &f) {
        SCOPED_TRACE(chc.label + ", frame " + std::to_string(f.index));
        EXPECT_EQ(differing_pixels(f), 0u);
        for (std::uint32_t leaf : cluster) {
            if (f.index >= 2 && f.index < 4) {
                EXPECT_FALSE(drew(f, leaf)) << "hidden leaf " << leaf << " drawn";
            }
            if (f.index == 4) {
                EXPECT_TRUE(drew(f, leaf)) << "leaf " << leaf << ", hidden last frame, not drawn in the frame that sees it";
            }
        }
    });
    for (const SessionStrategy &chc : session.strategies())
        EXPECT_EQ(chc.measured.frames(), cameras.size()) << chc.label;
}

// The first frame has no history: nothing is drawn untested, so tests run
// ahead of the results of the nodes in front of them would all find an
// empty depth buffer. It tests front to back instead, the nodes behind
// after what lies in front is drawn: from behind the wall the cluster is
// culled in the first frame already, whatever the passes and conditional
// draws, and the frame is the unculled one.
TEST(CoherentHierarchicalCulling, TheFirstFrameCullsWhatLiesBehindWhatItDraws)
{
    WallAndCluster s;
    const std::vector<std::uint32_t> cluster = s.cluster_leaves();
    ASSERT_FALSE(cluster.empty());
    MeasurementSession session(s.setup, s.ctx, checking_session_options());
    const std::vector<std::string> variants = {"chc", "chc:passes=shared", "chc:conditional=always",
                                               "chc:max-test-area=1", "chc:max-test-area=1:answer=exact"};
    for (const std::string &variant : variants)
        add_variant(session, StrategyTestVariant(variant));
    const Camera behind = looking({0, 0, 0}, {0, 0, -15});
    std::size_t frames = 0;
    session.walk({behind}, "chc", [&](const SessionStrategy &chc, const StrategyFrame &f) {
        SCOPED_TRACE(chc.label);
        ++frames;
        EXPECT_EQ(differing_pixels(f), 0u);
        EXPECT_GT(f.stats.leaves_drawn, 0u) << "the wall is drawn";
        for (std::uint32_t leaf : cluster)
            EXPECT_FALSE(drew(f, leaf)) << "leaf " << leaf << " behind the wall drawn in the first frame";
        EXPECT_GT(f.stats.nodes_occluded, 0u);
    });
    EXPECT_EQ(frames, variants.size());
}

namespace {

// Draws what chc asks for, and beside each leaf drawn conditionally a
// marker under the same condition: one stencil pixel (colour, depth and
// every other pixel untouched), so that the stencil buffer says which
// conditional draws the GL executed.
class MarkingSink final : public FrameSink {
public:
    explicit MarkingSink(const SceneRenderer &renderer) : renderer_(renderer) {}
    void draw_leaf(std::uint32_t node) override
    {
        renderer_.draw_leaf(node);
        plain.push_back(node);
        order.push_back(node);
    }
    void draw_leaf_conditionally(std::uint32_t node) override
    {
        renderer_.draw_leaf(node);
        mark(node);
        conditional.push_back(node);
        order.push_back(node);
    }
    void cull(std::uint32_t node, Visibility) override { culled.push_back(node); }
    void tested(std::uint32_t) override {}

    // The marker of leaf n: window pixel (2n + 1, 1).
    static int marker_x(std::uint32_t node) { return 2 * int(node) + 1; }

    std::vector<std::uint32_t> plain, conditional, culled;
    std::vector<std::uint32_t> order;   // plain and conditional, as drawn

private:
    static void mark(std::uint32_t node)
    {
        glPushAttrib(GL_ALL_ATTRIB_BITS);
        glMatrixMode(GL_PROJECTION);
        glPushMatrix();
        glLoadIdentity();
        GLint viewport[4];
        glGetIntegerv(GL_VIEWPORT, viewport);
        glOrtho(0, viewport[2], 0, viewport[3], -1, 1);
        glMatrixMode(GL_MODELVIEW);
        glPushMatrix();
        glLoadIdentity();
        glDisable(GL_CULL_FACE);
        glDepthFunc(GL_ALWAYS);
        glDepthMask(GL_FALSE);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_ALWAYS, 1, 0xFF);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        glBegin(GL_QUADS);
        const float x = float(marker_x(node));
        glVertex2f(x, 1);
        glVertex2f(x + 1, 1);
        glVertex2f(x + 1, 2);
        glVertex2f(x, 2);
        glEnd();
        glPopMatrix();
        glMatrixMode(GL_PROJECTION);
        glPopMatrix();
        glMatrixMode(GL_MODELVIEW);
        glPopAttrib();
    }

    const SceneRenderer &renderer_;
};

struct MarkedFrame {
    MarkingSink sink;
    std::vector<std::uint8_t> stencil;   // one row: y = 1

    bool marked(std::uint32_t node) const { return stencil.at(std::size_t(MarkingSink::marker_x(node))) != 0; }
    bool conditional(std::uint32_t node) const
    {
        return std::find(sink.conditional.begin(), sink.conditional.end(), node) != sink.conditional.end();
    }
};

// Leaves the frame in the context, its colour and depth.
MarkedFrame draw_marked(const WallAndCluster &s, Culler &culler, const Frame &frame)
{
    MarkedFrame m{MarkingSink(s.renderer), {}};
    glClearStencil(0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    gl::load_camera(frame.camera);
    culler.begin_frame(frame);
    own_traversal(culler)->traverse(m.sink);
    glFinish();
    m.stencil.resize(std::size_t(s.ctx.width()));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 1, s.ctx.width(), 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, m.stencil.data());
    return m;
}

// The visible pixels that the marked frame `m`, still in the context, lost
// (evaluation/lost_pixels.h): against the unculled frame drawn in chc's
// order, conditional draws the GL skipped included. Overwrites the frame.
std::uint64_t lost_pixels_of(const WallAndCluster &s, const MarkedFrame &m, const Camera &camera)
{
    const std::size_t pixels = std::size_t(s.ctx.width()) * std::size_t(s.ctx.height());
    return count_lost_pixels(s.renderer, s.setup.hierarchy(), camera, m.sink.order, nullptr, s.ctx.pixels(), pixels)
        .lost;
}

}  // namespace

// conditional=waits (the default: in place of the wait at the end of the
// traversal) and always (right after the pass): the cluster, hidden behind
// the wall, is tested every frame and its leaves are issued under
// conditional rendering on their tiles; the GL draws none of them (their markers stay unset). When the
// cluster comes into view the same conditional draws are executed, and the
// frame loses no pixel (evaluation/lost_pixels.h).
TEST(CoherentHierarchicalCulling, ConditionalDrawsOfPreviouslyHiddenLeavesAreDecidedByTheGL)
{
    const WallAndCluster s;
    // Both of occu's drivers have the async extension: its absence is a
    // missing feature, not a reason to skip.
    ASSERT_TRUE(gl::OcclusionUnit::async_available())
        << "GL_MESAX_occlusion_unit_async is absent from a driver of the patched Mesa";
    GLint stencil_bits = 0;
    glGetIntegerv(GL_STENCIL_BITS, &stencil_bits);
    ASSERT_GT(stencil_bits, 0);
    const StrategyContext context{s.setup.scene(), s.setup.hierarchy(), s.renderer};
    for (const char *conditional : {"waits", "always"}) {
    SCOPED_TRACE(std::string("conditional=") + conditional);
    const bool always = std::string(conditional) == "always";
    Strategy chc = make_strategy("chc:max-test-area=1:period=1:conditional=" + std::string(conditional), context);
    const std::vector<std::uint32_t> cluster = s.cluster_leaves();
    ASSERT_FALSE(cluster.empty());
    for (std::uint32_t leaf : cluster)
        ASSERT_LT(MarkingSink::marker_x(leaf), s.ctx.width());

    const Frame behind(looking({0, 0, 0}, {0, 0, -15}), 64, 64);
    const Frame beside(looking({12, 0, 0}, {0, 0, -15}), 64, 64);
    // As in the test above: visible in frame 0, drawn untested and found
    // hidden in frame 1, tested from frame 2 on.
    for (int f = 0; f < 5; ++f) {
        SCOPED_TRACE("frame " + std::to_string(f) + " behind the wall");
        const MarkedFrame m = draw_marked(s, *chc.culler, behind);
        EXPECT_EQ(lost_pixels_of(s, m, behind.camera), 0u);
        if (f < 2)
            continue;
        std::size_t issued = 0;
        for (std::uint32_t leaf : cluster) {
            EXPECT_EQ(std::count(m.sink.plain.begin(), m.sink.plain.end(), leaf), 0) << "hidden leaf " << leaf << " drawn unconditionally";
            if (!m.conditional(leaf))
                continue;   // under an inner node tested (and culled) as a whole
            ++issued;
            EXPECT_FALSE(m.marked(leaf)) << "hidden leaf " << leaf << ": its conditional draw was executed";
        }
        // waits: only where the result is not ready when the traversal
        // runs out of work (llvmpipe; softpipe's passes are done at their end).
        if (always) {
            EXPECT_GT(issued, 0u) << "no leaf of the hidden cluster was drawn conditionally: the test shows nothing";
        }
    }
    const MarkedFrame seen = draw_marked(s, *chc.culler, beside);
    EXPECT_EQ(lost_pixels_of(s, seen, beside.camera), 0u);
    std::size_t issued = 0;
    for (std::uint32_t leaf : cluster) {
        if (!seen.conditional(leaf))
            continue;
        ++issued;
        EXPECT_TRUE(seen.marked(leaf)) << "leaf " << leaf << ", hidden last frame and in view now: its conditional draw was not executed";
    }
    if (always) {
        EXPECT_GT(issued, 0u) << "no leaf of the cluster was drawn conditionally in the frame that sees it";
    }
    }
}

// A row of boxes all in view from a still camera: after the first frame,
// which tests down to the leaves, each leaf is re-tested once in every
// `period` frames (staggered by node), and no inner node is tested again.
TEST(CoherentHierarchicalCulling, VisibleLeavesAreRetestedOncePerPeriod)
{
    gl::OffscreenContext ctx(128, 128);
    Scene scene;
    scene.meshes.emplace_back();
    for (int i = 0; i < 12; ++i)
        append_box(scene.meshes[0], Aabb::of({float(i) * 1.2f - 7.0f, 0, -20}, {float(i) * 1.2f - 6.4f, 1, -19}));
    scene.update_bounds();
    const SceneSetup setup(std::move(scene), leaves_of_12_triangles());
    const std::uint32_t leaves = std::uint32_t(setup.hierarchy().leaf_count());
    const Camera camera = looking({0, 0.5f, 0}, {0, 0.5f, -20});
    // Counted, not drawn against references.
    SessionOptions so = checking_session_options();
    so.oracle = false;
    so.lost_pixels = SessionOptions::PixelCheck::none;

    for (const char *passes : {"disjoint", "shared"})
    for (std::uint32_t period : {1u, 4u, 7u}) {
        SCOPED_TRACE(std::string(passes) + " passes, period " + std::to_string(period));
        const bool shared = std::string(passes) == "shared";
        MeasurementSession session(setup, ctx, so);
        add_variant(session, StrategyTestVariant("chc:max-test-area=1:passes=" + std::string(passes) +
                                                 ":period=" + std::to_string(period)));
        std::uint32_t tested = 0, passes_after_first = 0;
        session.walk(std::vector<Camera>(2 * period + 1, camera), "chc", [&](const SessionStrategy &, const StrategyFrame &f) {
            EXPECT_EQ(f.stats.leaves_drawn, leaves) << "frame " << f.index << ": every box is in view";
            if (f.index == 0) {
                EXPECT_GT(f.stats.nodes_tested, 0u);
                return;
            }
            tested += f.stats.nodes_tested;
            passes_after_first += f.stats.passes;
            if (period > 1) {
                EXPECT_LT(f.stats.nodes_tested, leaves) << "frame " << f.index << " re-tested every leaf";
            }
        });
        EXPECT_EQ(tested, 2u * leaves) << "each visible leaf re-tested once per period, nothing else tested";
        if (shared) {
            EXPECT_LE(passes_after_first, 2u * period) << "at most one pass a frame: the re-tests share passes";
        }
    }
}

TEST(CoherentHierarchicalCulling, ConservativeOnlyAtThresholdZero)
{
    EXPECT_TRUE(choose_strategy("chc").conservative());
    EXPECT_TRUE(choose_strategy("chc:period=1:batch=1:bounds=1").conservative());
    EXPECT_FALSE(choose_strategy("chc:tolerance=0.05").conservative());
}
