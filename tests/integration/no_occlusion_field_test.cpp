// SPDX-License-Identifier: MIT
// The field (scene/field.h), the scene with no occlusion, and what the
// strategies do on it (issue 18, item 6). Nothing here is timed
// (occu-bench-no-occlusion measures the time); these check what can be
// checked without a clock:
//  - the field is what it claims: from the overhead route no leaf is
//    hidden by another (every leaf that shows pixels when drawn alone shows
//    pixels in the whole frame), while the same check finds hidden leaves
//    in the city, so that it can fail;
//  - every conservative strategy, with the walkthrough's policies across
//    frames (temporal coherence, switch-off 0.5: evaluation/measurement_session.h),
//    draws every frame of the route exactly as the unculled frame, as the
//    measurement session counts it (evaluation/lost_pixels.h);
//  - the switch-off engages: every strategy that has one tests no node in
//    the frames between its probes (frames 25-39 here: it switches off
//    after frame 0 and probes at frames 8, 24 and 56).
// Runs on the driver meson selects with GALLIUM_DRIVER.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "camera/route.h"
#include "culling/databases.h"
#include "culling/registry.h"
#include "evaluation/oracle.h"
#include "evaluation/measurement_session.h"
#include "gl/gl_headers.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "scene/city.h"
#include "scene/field.h"
#include "traversal/traversal.h"

#include "strategy_variants.h"

using namespace occu;

namespace {

// The benchmark's frame size. At a quarter of it the far posts are smaller
// than a pixel, and the one pixel centre of a leaf may fall on a post's
// foot, where the ground ties with it in depth and may keep the pixel.
constexpr int size = 512;

// Leaves in the frustum that show no pixel in the whole frame although
// they show some when drawn alone: leaves hidden by others.
std::vector<std::uint32_t> hidden_leaves(const gl::OffscreenContext &ctx, const SceneRenderer &renderer,
                                         const VisibilityTruth &truth, const Camera &camera)
{
    std::vector<std::uint32_t> unseen;
    std::set_difference(truth.in_frustum.begin(), truth.in_frustum.end(), truth.visible.begin(), truth.visible.end(),
                        std::back_inserter(unseen));
    std::vector<std::uint32_t> hidden;
    glClearColor(0, 0, 0, 0);
    for (std::uint32_t leaf : unseen) {
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gl::load_camera(camera);
        renderer.draw_leaf(leaf);
        glFinish();
        const std::uint8_t *p = ctx.pixels();
        bool shows = false;
        for (std::size_t i = 3; i < std::size_t(size) * size * 4 && !shows; i += 4)
            shows = p[i] != 0;
        if (shows)
            hidden.push_back(leaf);
    }
    return hidden;
}

}  // namespace

TEST(NoOcclusionField, NoLeafHidesAnotherFromTheOverheadRoute)
{
    gl::OffscreenContext ctx(size, size);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    const Scene field = generate_field(FieldOptions{});
    const Hierarchy h = Hierarchy::build(field);
    SceneRenderer renderer(field, h);
    Oracle oracle(renderer, h);
    std::size_t in_frustum = 0;
    for (const Camera &c : make_route("overhead", field.bounds, CityOptions{}, 6, 1.0f)) {
        const VisibilityTruth truth = oracle.see(c, size, size);
        in_frustum += truth.in_frustum.size();
        const std::vector<std::uint32_t> hidden = hidden_leaves(ctx, renderer, truth, c);
        EXPECT_TRUE(hidden.empty()) << hidden.size() << " of " << truth.in_frustum.size()
                                    << " leaves of the field hidden by others, the first " << (hidden.empty() ? 0 : hidden.front());
    }
    EXPECT_GT(in_frustum, 6u * 500u) << "the route sees too little of the field for the check to mean anything";

    // The check can fail: from the city's streets most leaves are hidden.
    CityOptions city;
    city.blocks_x = city.blocks_z = 3;
    const Scene town = generate_city(city);
    const Hierarchy th = Hierarchy::build(town);
    SceneRenderer town_renderer(town, th);
    Oracle town_oracle(town_renderer, th);
    const Camera c = make_route("dense", town.bounds, city, 1, 1.0f).front();
    const VisibilityTruth truth = town_oracle.see(c, size, size);
    EXPECT_GT(hidden_leaves(ctx, town_renderer, truth, c).size(), 50u) << "the check found no hidden leaf in the city";
}

TEST(NoOcclusionField, EveryStrategyDrawsUnculledFramesAndSwitchesOff)
{
    gl::OffscreenContext ctx(size, size);
    SceneChoice field;
    field.name = "field";
    const SceneSetup setup(field);
    // The walkthrough's policies across frames, each frame checked against
    // the unculled frame.
    SessionOptions so = integration::checking_session_options();
    so.coherence = true;
    so.switch_off = 0.5;
    MeasurementSession session(setup, ctx, so);
    for (const std::string &name : strategy_names()) {
        const StrategyChoice choice = choose_strategy(name);
        // Strategies that require a database (made for the scene) switch
        // off as the same family without one does.
        const auto read = databases_read(choice);
        if (choice.conservative() &&
            std::none_of(read.begin(), read.end(), [](const DatabaseNeed *d) { return d->required; }))
            session.add(name);
    }
    std::map<std::string, std::uint64_t> tested_between_probes;
    session.walk(setup.route("overhead", 40), "field", [&](const SessionStrategy &s, const StrategyFrame &f) {
        EXPECT_EQ(integration::differing_pixels(f), 0u) << s.label << ", frame " << f.index;
        if (f.index >= 25)
            tested_between_probes[s.label] += f.stats.nodes_tested;
    });

    std::size_t with_switch_off = 0;
    for (const SessionStrategy &s : session.strategies()) {
        EXPECT_EQ(s.measured.frames(), 40u) << s.label;
        if (s.policies.switch_off) {
            ++with_switch_off;
            EXPECT_EQ(tested_between_probes[s.label], 0u)
                << s.label << ": node tests in frames 25-39: the switch-off did not engage";
        }
    }
    // Every family that tests occlusion has one: all but none, vfc, ideal and pvs.
    EXPECT_GE(with_switch_off, 20u);
}
