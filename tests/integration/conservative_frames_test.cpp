// SPDX-License-Identifier: MIT
// Conservative strategies never remove a visible pixel: on short routes of
// a small city and random views inside it, every frame of every
// conservative strategy in the registry and of every test variant its
// family declares (other settings, strictly front to back, in batches,
// with temporal coherence, with the switch-off's probes: culling/registry.h),
// from the databases they require, made here, equals the unculled frame
// byte for byte, as the measurement session counts it (no pixel lost, none
// different through depth ties: evaluation/lost_pixels.h); and every
// strategy but the unculled and frustum-culled references draws fewer
// triangles than view-frustum culling (so the comparison can fail), ideal
// no more than any, and each variant within the bounds its family
// declares. Runs on the driver meson selects with GALLIUM_DRIVER.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "culling/databases.h"
#include "culling/registry.h"
#include "evaluation/measurement_session.h"
#include "gl/offscreen_context.h"

#include "small_city.h"
#include "strategy_variants.h"

using namespace occu;
using namespace occu::integration;

namespace {

// The databases the strategies require, made by the database provider
// (culling/databases.h) for the small city, smaller than by default: 5 x 5
// grid points, 4 headings each, maps of 32 x 32 for the 128 x 128 frames.
const std::vector<std::string> small_databases = {"database-grid=5", "database-headings=4"};

}  // namespace

TEST(ConservativeCulling, EveryConservativeVariantEqualsUnculledFrames)
{
    // A city of 4x4 blocks in leaves of at most 128 triangles, 128x128 frames.
    SmallCity small(4, 128, 128);
    // Per process: meson runs this binary once per driver, at the same time.
    DatabaseProvider databases(::testing::TempDir() + "occu-small-city-databases-" + std::to_string(getpid()),
                               DatabaseProvider::Makes::required, nullptr);
    MeasurementSession session(small.setup, small.ctx, checking_session_options(&databases));
    const std::vector<StrategyTestVariant> variants = conservative_test_variants();
    for (const StrategyTestVariant &v : variants)
        add_variant(session, v, small_databases);

    // The city's routes, and random views from inside its bounds (eyes in
    // buildings and streets alike, looking anywhere).
    std::size_t index = 0;
    for (const char *route : {"dense", "medium", "open", "random:6:2026"})
        for (const Camera &camera : small.setup.route(route, 5))
            session.measure(index++, camera, [&](const SessionStrategy &s, const StrategyFrame &f) {
                EXPECT_EQ(differing_pixels(f), 0u)
                    << s.label << ", " << route << " frame " << f.index << " (" << f.loss.lost << " lost, "
                    << f.loss.tied << " through depth ties); visible leaves not drawn:" << visible_leaves_not_drawn(f);
            });
    std::filesystem::remove_all(databases.directory());

    std::map<std::string, double> drawn;
    for (const SessionStrategy &s : session.strategies()) {
        ASSERT_EQ(s.measured.frames(), index) << s.label;
        drawn[s.label] = s.measured.triangles;
        std::printf("%-64s %12.0f triangles\n", s.label.c_str(), s.measured.triangles);
    }
    const std::string none = "none/16", vfc = "vfc/16", ideal = "ideal/16";
    ASSERT_GT(drawn[none], 0.0);
    ASSERT_LT(drawn[vfc], drawn[none]);
    for (const auto &[label, triangles] : drawn) {
        if (label != none && label != vfc) {
            EXPECT_LT(triangles, drawn[vfc]) << label << " culled no more than vfc";
        }
        EXPECT_LE(drawn[ideal], triangles) << label << " drew less than the oracle sees";
    }
    EXPECT_GT(expect_declared_bounds(session, variants), 0u);
}

// The same at a distance: the default city seen from the open route, where
// depth resolution is coarse and proxy faces lie on the surfaces they bound.
TEST(ConservativeCulling, FramesEqualUnculledFramesFarAway)
{
    gl::OffscreenContext ctx(256, 256);
    const SceneSetup city{SceneChoice{}};
    SessionOptions so = checking_session_options();
    so.oracle = false;
    MeasurementSession session(city, ctx, so);
    for (const char *spec : {"none", "ou:max-test-area=1"})
        add_variant(session, StrategyTestVariant(spec).in_batches_of(so.batch));
    session.walk(city.route("open", 3), "open", [&](const SessionStrategy &s, const StrategyFrame &f) {
        EXPECT_EQ(differing_pixels(f), 0u) << s.label << ", open frame " << f.index;
    });
    EXPECT_LT(session.strategies()[1].measured.triangles, session.strategies()[0].measured.triangles)
        << "ou culled nothing";
}
