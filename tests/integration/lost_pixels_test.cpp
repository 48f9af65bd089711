// SPDX-License-Identifier: MIT
// The lost-pixel counter (evaluation/lost_pixels.h), which occu-random-views
// trusts to say that a conservative strategy lost nothing: on random views
// of a small city it counts 0 for vfc, ou and chc (chc against its
// reference alone, the others first against the common unculled frame),
// and finds the pixels of a deliberately broken culler, vfc that drops one
// leaf the oracle sees, in every view, by both routes.
// Runs on the driver meson selects with GALLIUM_DRIVER.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "camera/route.h"
#include "culling/registry.h"
#include "evaluation/lost_pixels.h"
#include "evaluation/oracle.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "scene/city.h"
#include "traversal/traversal.h"

using namespace occu;

namespace {

// A broken culler: `inner`'s answers, but leaf `dropped` is occluded.
class DropOneLeaf : public Culler {
public:
    DropOneLeaf(Culler &inner, std::uint32_t dropped) : inner_(inner), dropped_(dropped) {}
    void begin_frame(const Frame &frame) override { inner_.begin_frame(frame); }
    void test(std::vector<NodeTest> &tests) override
    {
        inner_.test(tests);
        for (NodeTest &t : tests)
            if (t.node == dropped_)
                t.result = Visibility::occluded;
    }

private:
    Culler &inner_;
    std::uint32_t dropped_;
};

constexpr int size = 128;

// The frame `culler` draws through the common traversal; its drawn leaves.
std::vector<std::uint32_t> draw(const SceneRenderer &renderer, const Hierarchy &h, Culler &culler, const Frame &frame)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl::load_camera(frame.camera);
    TraversalOptions options;
    options.batch = 32;
    FrameStats s = render_hierarchy(renderer, h, culler, frame, options);
    glFinish();
    return std::move(s.drawn);
}

std::vector<std::uint8_t> pixels(const gl::OffscreenContext &ctx)
{
    return std::vector<std::uint8_t>(ctx.pixels(), ctx.pixels() + std::size_t(size) * size * 4);
}

}  // namespace

TEST(LostPixels, CountsNoneForConservativeStrategiesAndFindsADroppedVisibleLeaf)
{
    gl::OffscreenContext ctx(size, size);
    CityOptions city;
    city.blocks_x = city.blocks_z = 4;
    const Scene scene = generate_city(city);
    HierarchyOptions ho;
    ho.max_leaf_triangles = 128;
    const Hierarchy h = Hierarchy::build(scene, ho);
    const SceneRenderer renderer(scene, h);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glClearColor(0.55f, 0.7f, 0.9f, 1.0f);
    const StrategyContext context{scene, h, renderer};
    Strategy none = make_strategy("none", context), vfc = make_strategy("vfc", context),
             ou = make_strategy("ou", context), chc = make_strategy("chc", context);
    Oracle oracle(renderer, h);
    const std::size_t n = std::size_t(size) * size;

    const std::vector<Camera> views = random_views(scene.bounds, 12, 2026, 1.0f, 30.0f, 90.0f);
    int broken_views = 0;
    for (std::size_t v = 0; v < views.size(); ++v) {
        SCOPED_TRACE("view " + std::to_string(v));
        const VisibilityTruth truth = oracle.see(views[v], size, size);
        const Frame frame(views[v], size, size, &truth);
        draw(renderer, h, *none.culler, frame);
        const std::vector<std::uint8_t> unculled = pixels(ctx);
        for (Strategy *s : {&vfc, &ou}) {
            const std::vector<std::uint32_t> drawn = draw(renderer, h, *s->culler, frame);
            const PixelLoss loss = count_lost_pixels(renderer, h, views[v], drawn, unculled.data(), ctx.pixels(), n);
            EXPECT_EQ(loss.lost, 0u) << s->choice.label();
            EXPECT_EQ(loss.tied, 0u) << s->choice.label();
        }
        const std::vector<std::uint32_t> chc_leaves = draw(renderer, h, *chc.culler, frame);
        EXPECT_EQ(count_lost_pixels(renderer, h, views[v], chc_leaves, nullptr, ctx.pixels(), n).lost, 0u) << "chc";

        if (truth.visible.empty())
            continue;
        // The broken culler drops one leaf the oracle sees: at least one of its pixels is lost.
        const std::uint32_t dropped = truth.visible[v % truth.visible.size()];
        DropOneLeaf broken(*vfc.culler, dropped);
        const std::vector<std::uint32_t> drawn = draw(renderer, h, broken, frame);
        ASSERT_EQ(std::count(drawn.begin(), drawn.end(), dropped), 0) << "the broken culler drew leaf " << dropped;
        const std::vector<std::uint8_t> broken_frame = pixels(ctx);
        const PixelLoss against_unculled =
            count_lost_pixels(renderer, h, views[v], drawn, unculled.data(), ctx.pixels(), n);
        EXPECT_GT(against_unculled.lost, 0u) << "leaf " << dropped << " dropped, no pixel lost";
        std::copy(broken_frame.begin(), broken_frame.end(), ctx.pixels_mutable());
        EXPECT_EQ(count_lost_pixels(renderer, h, views[v], drawn, nullptr, ctx.pixels(), n).lost, against_unculled.lost)
            << "the reference alone counts otherwise";
        ++broken_views;
    }
    EXPECT_GE(broken_views, 6) << "too few views see anything for the broken culler to mean much";
}
