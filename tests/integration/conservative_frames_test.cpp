// SPDX-License-Identifier: MIT
// Conservative strategies never remove a visible pixel: on short routes of
// a small city and random views inside it, every frame of every conservative strategy in the registry
// (and of its traversal variants: strictly front to back, in batches, with
// temporal coherence, leaves tested by their triangles, from the databases
// they require, made here) equals the unculled frame byte
// for byte, while the occlusion strategies draw fewer triangles (so the
// comparison can fail). Runs on the driver meson selects with GALLIUM_DRIVER.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <vector>

#include "camera/route.h"
#include "culling/databases.h"
#include "culling/registry.h"
#include "evaluation/oracle.h"
#include "gl/offscreen_context.h"
#include "gl/state.h"
#include "scene/city.h"
#include "strategies/poon_wang_opacity_maps/occluder_database.h"
#include "strategies/poon_wang_opacity_maps/view_preprocessing.h"
#include "traversal/traversal.h"

#include "frame_comparison.h"
#include "small_city.h"

using namespace occu;
using occu::integration::draw_frame;
using occu::integration::DrawnFrame;

namespace {

// The databases the strategies require, made by the database provider
// (culling/databases.h) for the small city, smaller than by default: 5 x 5
// grid points, 4 headings each, maps of 32 x 32 for the 128 x 128 frames.
const std::vector<std::string> small_databases = {"database-grid=5", "database-headings=4"};

struct Variant {
    std::string spec;
    std::size_t batch = 16;
    bool coherence = false;
    // Switched off after the first frame, probing as soon as it can (frames
    // 1, 3, 7 and 15 of the 20 of its routes): the switch-off's probes (inner nodes only,
    // Frame::probe, chc through the common traversal) stay exact.
    bool probes = false;
};

}  // namespace

TEST(ConservativeCulling, EveryConservativeStrategyEqualsUnculledFrames)
{
    // A city of 4x4 blocks in leaves of at most 128 triangles, 128x128 frames.
    const integration::SmallCity small(4, 128, 128);
    const Hierarchy &h = small.h;
    const SceneRenderer &renderer = small.renderer;
    const StrategyContext context{small.scene, h, renderer};
    // Per process: meson runs this binary once per driver, at the same time.
    DatabaseProvider databases(::testing::TempDir() + "occu-small-city-databases-" + std::to_string(getpid()),
                               DatabaseProvider::Makes::required, nullptr);
    glClearColor(0, 0, 0, 0);

    // Every listed strategy, and the traversal variants of the occlusion unit.
    std::vector<Variant> variants;
    for (const std::string &name : strategy_names())
        if (choose_strategy(name).conservative())
            variants.push_back({name});
    variants.push_back({"ou:max-test-area=1", 1});
    variants.push_back({"ou:max-test-area=1", 16});
    variants.push_back({"ou:proxy=triangles:max-test-area=1", 16});
    variants.push_back({"hp:proxy=triangles", 16});
    variants.push_back({"ou-shared", 32, true});
    variants.push_back({"om-ps", 16, true});
    variants.push_back({"om-ps:occluder-triangle-budget=2048", 16});
    // The scene's own triangles beside the skins, for every family that takes them.
    for (const char *triangles : {"skins:occluder-triangles=512", "hzb:occluder-triangles=512", "hom:occluder-triangles=512",
                                  "skins:occluder-triangles=512:coverage=merged",
                                  "hzb:occluder-triangles=512:coverage=merged",
                                  "skins:occluder-triangles=512:coverage=merged:occludee=triangles"})
        variants.push_back({triangles});
    for (const char *probed : {"ou", "hp", "om-fh", "pc-fh", "skins-drawn", "chc"})
        variants.push_back({probed, 16, false, true});

    const Strategy none = make_strategy("none", context);
    Oracle oracle(renderer, h);
    std::map<std::string, std::uint64_t> drawn;
    std::uint64_t drawn_none = 0;
    for (const Variant &v : variants) {
        SCOPED_TRACE(v.spec);
        std::vector<std::string> settings = small_databases;
        for (const std::string &d : databases.settings_for(choose_strategy(v.spec, small_databases), context, 128, 128))
            settings.push_back(d);
        Strategy s = make_strategy(v.spec, context, settings);
        VisibleNodeList coherence(3);
        TraversalOptions options;
        options.batch = v.batch;
        if (v.coherence)
            options.policies.push_back(&coherence);
        SwitchOff::Settings probe_every_frame;
        probe_every_frame.min_gain = 1e9;
        probe_every_frame.probe_period = 1;
        SwitchOff switch_off(probe_every_frame);
        if (v.probes)
            options.policies.push_back(&switch_off);
        const std::string key =
            v.spec + "/" + std::to_string(v.batch) + (v.coherence ? "/coherent" : "") + (v.probes ? "/probes" : "");
        // The city's routes, and random views from inside its bounds (eyes in
        // buildings and streets alike, looking anywhere).
        for (const char *route : {"dense", "medium", "open", "random:6:2026"}) {
            const auto cameras = small.setup.route(route, 5);
            for (std::size_t f = 0; f < cameras.size(); ++f) {
                const VisibilityTruth truth = oracle.see(cameras[f], 128, 128);
                const Frame frame(cameras[f], 128, 128, &truth);
                const DrawnFrame reference = draw_frame(small.ctx, renderer, h, *none.culler, frame, {});
                const DrawnFrame culled = draw_frame(small.ctx, renderer, h, *s.culler, frame, options);
                // A strategy that orders the frame itself: the unculled frame in its order.
                const bool ordered = orders_frame(*s.culler);
                const std::vector<std::uint8_t> in_order =
                    ordered ? integration::draw_unculled_after(small.ctx, renderer, h, frame, culled.leaves).pixels
                            : std::vector<std::uint8_t>{};
                EXPECT_TRUE((ordered ? in_order : reference.pixels) == culled.pixels) << route << " frame " << f << ": " << key;
                drawn[key] += culled.triangles;
                if (v.spec == "none")
                    drawn_none += reference.triangles;
            }
        }
    }
    ASSERT_GT(drawn_none, 0u);
    for (const char *occluding : {"ideal/16", "ou/16", "ou-shared/16", "hp/16", "om-ps/16", "om-fh/16", "om-mos/16",
                                  "skins/16", "skins-drawn/16", "hzb/16", "hom/16", "shadow/16", "planes/16",
                                  "pc-mos/16", "ou:max-test-area=1/1", "chc/16",
                                  "skins:occluder-triangles=512/16", "hzb:occluder-triangles=512/16",
                                  "hom:occluder-triangles=512/16", "skins:occluder-triangles=512:coverage=merged/16",
                                  "om-ps:occluder-triangle-budget=2048/16",
                                  "skins:occluder-triangles=512:coverage=merged:occludee=triangles/16",
                                  "hzb:occluder-triangles=512:coverage=merged/16"})
        EXPECT_LT(drawn[occluding], drawn["vfc/16"]) << occluding << " culled no more than vfc";
    for (const char *family : {"skins", "hzb"})
        EXPECT_LE(drawn[std::string(family) + ":occluder-triangles=512:coverage=merged/16"],
                  drawn[std::string(family) + ":occluder-triangles=512/16"])
            << family << ": merged coverage should cull at least what whole depth pixels do";
    EXPECT_LE(drawn["skins:occluder-triangles=512:coverage=merged:occludee=triangles/16"],
              drawn["skins:occluder-triangles=512:coverage=merged/16"])
        << "a leaf tested by its triangles, where its box fails, is culled at least as often";
    EXPECT_LT(drawn["ou:max-test-area=1/16"], drawn_none / 2) << "ou culled too little for the comparison to mean anything";
    EXPECT_LE(drawn["ou:proxy=triangles:max-test-area=1/16"], drawn["ou:max-test-area=1/16"])
        << "triangles as proxies should cull at least what boxes do";
    EXPECT_LE(drawn["hp:proxy=triangles/16"], drawn["hp/16"]) << "triangles as proxies should cull at least what boxes do";
    EXPECT_LE(drawn["ideal/16"], drawn["ou:max-test-area=1/1"]) << "nothing culls more than the floor";
    std::filesystem::remove_all(databases.directory());
    // A query counts the whole grown proxy, a tile only the box's footprint:
    // hp sees at least the fragments ou does, so it draws about as much or more.
    EXPECT_GE(drawn["hp/16"], drawn["ou:max-test-area=1/16"] * 99 / 100);
}

// The same at a distance: the default city seen from the open route, where
// depth resolution is coarse and proxy faces lie on the surfaces they bound.
TEST(ConservativeCulling, FramesEqualUnculledFramesFarAway)
{
    gl::OffscreenContext ctx(256, 256);
    const SceneSetup city{SceneChoice{}};
    const Hierarchy &h = city.hierarchy();
    SceneRenderer renderer(city.scene(), h);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    const StrategyContext context{city.scene(), h, renderer};
    const Strategy none = make_strategy("none", context), ou = make_strategy("ou:max-test-area=1", context);
    const auto cameras = city.route("open", 3);
    std::uint64_t drawn_none = 0, drawn_ou = 0;
    for (std::size_t f = 0; f < cameras.size(); ++f) {
        const Frame frame(cameras[f], 256, 256);
        const DrawnFrame reference = draw_frame(ctx, renderer, h, *none.culler, frame, {});
        const DrawnFrame culled = draw_frame(ctx, renderer, h, *ou.culler, frame, {});
        EXPECT_TRUE(reference.pixels == culled.pixels) << "open frame " << f;
        drawn_none += reference.triangles;
        drawn_ou += culled.triangles;
    }
    EXPECT_LT(drawn_ou, drawn_none) << "ou culled nothing";
}
