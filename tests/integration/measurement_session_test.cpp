// SPDX-License-Identifier: MIT
// The measurement session (evaluation/measurement_session.h) every
// comparing program runs, and the scene setup it runs over
// (evaluation/scene_setup.h):
//  - the strategies' order is shuffled per frame, not rotated: a
//    strategy's successor changes from frame to frame, the same seed gives
//    the same orders and another seed others;
//  - what it measures is the frames': totals equal the sums of what the
//    observer was shown, ideal culls no visible leaf and every occluded
//    one, vfc no occluded one, an approximate strategy loses pixels and a
//    conservative one none, and the observer sees the strategy's own
//    frame, not the reference the lost pixels were counted against;
//  - a scene setup names a missing file, and another hierarchy over it
//    shares its scene.
// Runs on the driver meson selects with GALLIUM_DRIVER.
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "evaluation/lost_pixels.h"
#include "evaluation/measurement_session.h"
#include "gl/offscreen_context.h"

using namespace occu;

namespace {

constexpr int size = 64;

SceneSetup small_city()
{
    SceneChoice choice;
    choice.city.blocks_x = choice.city.blocks_z = 3;
    choice.hierarchy.max_leaf_triangles = 128;
    return SceneSetup(choice);
}

// The order the strategies drew each of `frames` frames in.
std::vector<std::vector<std::string>> orders(const SceneSetup &setup, gl::OffscreenContext &ctx, std::uint64_t seed,
                                             int frames)
{
    SessionOptions so;
    so.oracle = false;
    so.lost_pixels = SessionOptions::PixelCheck::none;
    so.order_seed = seed;
    MeasurementSession session(setup, ctx, so);
    for (const char *name : {"none", "vfc", "ou", "hp", "om-ps"})
        session.add(name);
    std::vector<std::vector<std::string>> drawn(std::size_t(frames), std::vector<std::string>{});
    session.walk(setup.route("dense", frames), "orders",
                 [&](const SessionStrategy &s, const StrategyFrame &f) { drawn[f.index].push_back(s.label); });
    return drawn;
}

}  // namespace

TEST(MeasurementSession, ShufflesTheOrderPerFrameFromItsSeed)
{
    const SceneSetup setup = small_city();
    gl::OffscreenContext ctx(size, size);
    const auto a = orders(setup, ctx, 1998, 12), again = orders(setup, ctx, 1998, 12), other = orders(setup, ctx, 7, 12);
    EXPECT_EQ(a, again) << "the same seed gave other orders";
    EXPECT_NE(a, other) << "another seed gave the same orders";
    // Each frame every strategy once.
    for (const auto &order : a)
        EXPECT_EQ(std::set<std::string>(order.begin(), order.end()).size(), 5u);
    // In a rotation a strategy is always followed by the same one; here vfc
    // is followed by several, and the first place changes hands.
    std::set<std::string> after_vfc, first;
    for (const auto &order : a) {
        first.insert(order.front());
        for (std::size_t i = 0; i + 1 < order.size(); ++i)
            if (order[i] == "vfc")
                after_vfc.insert(order[i + 1]);
    }
    EXPECT_GE(after_vfc.size(), 3u) << "vfc is followed by too few strategies for a shuffle";
    EXPECT_GE(first.size(), 3u);
}

TEST(MeasurementSession, MeasuresEachStrategysOwnFrames)
{
    const SceneSetup setup = small_city();
    gl::OffscreenContext ctx(size, size);
    SessionOptions so;
    so.lost_pixels = SessionOptions::PixelCheck::all;
    MeasurementSession session(setup, ctx, so);
    for (const char *name : {"vfc", "ideal", "ou", "ou:tolerance=0.9"})
        session.add(name);
    EXPECT_THROW(session.add("no-such-strategy"), std::invalid_argument);
    const Strategy none = make_strategy("none", session.context());

    struct Seen {
        std::uint64_t frames = 0, lost = 0, faults = 0, different_from_reference = 0;
        double ms = 0;
    };
    std::map<std::string, Seen> seen;
    session.walk(setup.route("dense", 8), "session", [&](const SessionStrategy &s, const StrategyFrame &f) {
        Seen &x = seen[s.label];
        x.frames += 1;
        x.ms += f.ms;
        x.faults += f.page_faults;
        x.lost += f.loss.lost;
        EXPECT_TRUE(f.pixels_checked) << s.label;
        EXPECT_GT(f.ms, 0.0) << s.label;
        // The context holds the strategy's frame: where it lost pixels it
        // differs from the unculled frame drawn in its order.
        if (f.loss.lost) {
            const std::vector<std::uint8_t> own(ctx.pixels(), ctx.pixels() + std::size_t(size) * size * 4);
            draw_unculled_after(session.renderer(), setup.hierarchy(), f.frame->camera, f.stats.drawn);
            x.different_from_reference += lost_pixels(ctx.pixels(), own.data(), std::size_t(size) * size);
        }
    });
    ASSERT_EQ(session.strategies().size(), 4u);
    for (const SessionStrategy &s : session.strategies()) {
        SCOPED_TRACE(s.label);
        const Measured &m = s.measured;
        const Seen &x = seen[s.label];
        EXPECT_EQ(m.frames(), 8u);
        EXPECT_EQ(x.frames, 8u);
        EXPECT_NEAR(m.mean_ms() * 8, x.ms, 1e-9 * x.ms + 1e-9);
        EXPECT_EQ(m.page_faults, x.faults);
        EXPECT_EQ(m.lost_pixels, x.lost);
        EXPECT_EQ(x.different_from_reference, x.lost) << "the observer was shown the reference, not the frame";
        ASSERT_TRUE(m.efficiency_percent()) << "the dense route hides nothing";
    }
    const Measured &vfc = session.strategies()[0].measured, &ideal = session.strategies()[1].measured,
                   &ou = session.strategies()[2].measured, &rough = session.strategies()[3].measured;
    EXPECT_EQ(*vfc.efficiency_percent(), 0.0);
    EXPECT_EQ(*ideal.efficiency_percent(), 100.0);
    EXPECT_EQ(ideal.visible_culled, 0u);
    EXPECT_EQ(ou.lost_pixels, 0u);
    EXPECT_GT(*ou.efficiency_percent(), 0.0);
    EXPECT_GT(rough.lost_pixels, 0u) << "ou:tolerance=0.9 lost no pixel: the check cannot fail";
    EXPECT_EQ(session.reference_ms("vfc"), vfc.mean_ms());
    EXPECT_EQ(session.reference_ms("ideal"), ideal.mean_ms());
    EXPECT_EQ(session.reference_ms("none"), 0.0);
}

TEST(MeasurementSession, ChecksOnlyApproximateFramesByDefaultAndNeedsTheOracleForIdeal)
{
    const SceneSetup setup = small_city();
    gl::OffscreenContext ctx(size, size);
    {
        MeasurementSession session(setup, ctx);
        session.add("ou");
        session.add("ou:tolerance=0.9");
        std::map<std::string, bool> checked;
        session.walk(setup.route("dense", 2), "session",
                     [&](const SessionStrategy &s, const StrategyFrame &f) { checked[s.label] = f.pixels_checked; });
        EXPECT_FALSE(checked["ou"]);
        EXPECT_TRUE(checked["ou:tolerance=0.9"]);
    }
    SessionOptions no_oracle;
    no_oracle.oracle = false;
    MeasurementSession session(setup, ctx, no_oracle);
    EXPECT_THROW(session.add("ideal"), std::invalid_argument);
    session.add("vfc");
    session.walk(setup.route("dense", 2), "session");
    EXPECT_FALSE(session.strategies()[0].measured.efficiency_percent()) << "efficiency without an oracle";
}

TEST(SceneSetup, NamesAMissingFileAndSharesItsSceneAcrossHierarchies)
{
    SceneChoice missing;
    missing.name = "/nonexistent/scene.obj";
    try {
        SceneSetup setup(missing);
        ADD_FAILURE() << "a missing scene file was read";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("'/nonexistent/scene.obj': no such file"), std::string::npos) << e.what();
    }
    const SceneSetup setup = small_city();
    HierarchyOptions coarse;
    coarse.max_leaf_triangles = 1024;
    const SceneSetup other = setup.with_hierarchy(coarse);
    EXPECT_EQ(&other.scene(), &setup.scene());
    EXPECT_LT(other.hierarchy().leaf_count(), setup.hierarchy().leaf_count());
    EXPECT_EQ(setup.name(), "city");
    EXPECT_EQ(setup.route("dense", 5).size(), 5u);
}
