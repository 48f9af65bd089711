// SPDX-License-Identifier: MIT
// The lost-pixel counter (evaluation/lost_pixels.h), which the measurement
// session applies for occu-random-views and for every integration test to
// say that a conservative strategy lost nothing: on random views of a
// small city it counts 0 for vfc, ou and chc (chc against its reference
// alone, the others first against the common unculled frame), and finds
// the pixels of a deliberately broken culler, vfc that drops one leaf the
// oracle sees, in every view, by both routes.
// Runs on the driver meson selects with GALLIUM_DRIVER.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "culling/registry.h"
#include "evaluation/lost_pixels.h"
#include "evaluation/measurement_session.h"
#include "gl/offscreen_context.h"

#include "small_city.h"
#include "strategy_variants.h"

using namespace occu;

namespace {

// A broken culler: `inner`'s answers, but one leaf the oracle sees is
// occluded, in frame v the (v mod n)-th of the n it sees.
class DropOneVisibleLeaf : public Culler {
public:
    explicit DropOneVisibleLeaf(std::unique_ptr<Culler> inner) : inner_(std::move(inner)) {}
    void begin_frame(const Frame &frame) override
    {
        const auto &visible = frame.truth->visible;
        dropped_ = visible.empty() ? none : visible[frames_ % visible.size()];
        ++frames_;
        inner_->begin_frame(frame);
    }
    void test(std::vector<NodeTest> &tests) override
    {
        inner_->test(tests);
        for (NodeTest &t : tests)
            if (t.node == dropped_)
                t.result = Visibility::occluded;
    }
    // The leaf dropped in the last frame (none: the oracle saw nothing).
    std::uint32_t dropped() const { return dropped_; }
    static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();

private:
    std::unique_ptr<Culler> inner_;
    std::uint32_t dropped_ = none;
    std::size_t frames_ = 0;
};

constexpr int size = 128;

}  // namespace

TEST(LostPixels, CountsNoneForConservativeStrategiesAndFindsADroppedVisibleLeaf)
{
    gl::OffscreenContext ctx(size, size);
    const SceneSetup setup(integration::small_city_choice(4, 128));
    SessionOptions so = integration::checking_session_options();
    so.clear_colour[0] = 0.55f, so.clear_colour[1] = 0.7f, so.clear_colour[2] = 0.9f, so.clear_colour[3] = 1.0f;
    MeasurementSession session(setup, ctx, so);
    for (const char *name : {"vfc", "ou", "chc"})
        session.add(name);
    Strategy vfc = make_strategy("vfc", session.context());
    auto broken_culler = std::make_unique<DropOneVisibleLeaf>(std::move(vfc.culler));
    const DropOneVisibleLeaf &broken = *broken_culler;
    session.add(Strategy{vfc.choice, std::move(broken_culler)}, "broken");

    const std::size_t n = std::size_t(size) * size;
    int broken_views = 0;
    session.walk(setup.random_views(12, 2026, 30.0f, 90.0f), "views", [&](const SessionStrategy &s, const StrategyFrame &f) {
        SCOPED_TRACE(s.label + ", view " + std::to_string(f.index));
        ASSERT_TRUE(f.pixels_checked);
        if (s.label == "chc") {
            EXPECT_EQ(f.loss.lost, 0u);
            return;
        }
        if (s.label != "broken") {
            EXPECT_EQ(f.loss.lost, 0u);
            EXPECT_EQ(f.loss.tied, 0u);
            return;
        }
        if (broken.dropped() == DropOneVisibleLeaf::none)
            return;
        // The broken culler drops one leaf the oracle sees: at least one of its pixels is lost.
        ASSERT_EQ(std::count(f.stats.drawn.begin(), f.stats.drawn.end(), broken.dropped()), 0)
            << "the broken culler drew leaf " << broken.dropped();
        EXPECT_GT(f.loss.lost, 0u) << "leaf " << broken.dropped() << " dropped, no pixel lost";
        // The context holds the broken frame: the reference alone counts the same.
        EXPECT_EQ(count_lost_pixels(session.renderer(), setup.hierarchy(), f.frame->camera, f.stats.drawn, nullptr,
                                    ctx.pixels(), n)
                      .lost,
                  f.loss.lost)
            << "the reference alone counts otherwise";
        ++broken_views;
    });
    EXPECT_GE(broken_views, 6) << "too few views see anything for the broken culler to mean much";
}
