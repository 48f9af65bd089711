// SPDX-License-Identifier: MIT
// Shadow culling (Moeller and Haines, "Occlusion Culling Algorithms",
// section "Shadow Culling": `shadow`, Hudson et al.; `planes`, Coorg and
// Teller), and every other strategy whose occluders are occluder skins
// (the registry's conservative names and test variants of the families
// that read a skin database: skins, hzb, hom), where skins would hide what
// GL shows: the eye inside a mesh (back-face culling then shows what lies
// behind the mesh's skin) and a near plane that clips away the mesh's
// surface in front of a skin. In both the strategies must leave the skin
// out (SkinOccluders::usable), and their frames equal the unculled frames
// byte for byte, as the measurement session counts them, as on many random
// views of a small city; and the
// two families, equivalent for single convex occluders, draw the same
// leaves. Runs on the driver meson selects with GALLIUM_DRIVER.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "camera/route.h"
#include "culling/databases.h"
#include "culling/registry.h"
#include "evaluation/measurement_session.h"
#include "gl/offscreen_context.h"
#include "occluders/skin_occluders.h"
#include "scene/city.h"

#include "small_city.h"
#include "strategy_variants.h"

using namespace occu;
using namespace occu::integration;

namespace {

bool holds(const Aabb &outer, const Aabb &inner)
{
    return glm::all(glm::lessThanEqual(outer.min, inner.min)) && glm::all(glm::lessThanEqual(inner.max, outer.max));
}

// Cameras that would see through a skin's mesh: for skins of meshes away
// from the city's edge, an eye just outside the skin (inside its mesh)
// looking through it, and an eye outside the mesh whose near plane cuts
// into the mesh's bounds in front of the skin.
std::vector<Camera> through_the_mesh_cameras(const Scene &scene, const std::vector<Aabb> &skins, int count)
{
    std::vector<Camera> cameras;
    const Camera lens = street_level_lens(scene.bounds, 1.0f);
    for (std::size_t s = 0; s < skins.size() && int(cameras.size()) < 2 * count; s += skins.size() / std::size_t(count)) {
        const Aabb &skin = skins[s];
        for (const Mesh &m : scene.meshes) {
            Aabb bounds;
            for (const glm::vec3 &p : m.positions)
                bounds.expand(p);
            if (!holds(bounds, skin) || bounds.extent().y < 1.0f)
                continue;
            const glm::vec3 c = skin.center();
            Camera inside = lens;
            inside.position = {skin.min.x - 0.02f, c.y, c.z};
            inside.target = inside.position + glm::vec3(1.0f, 0.0f, 0.1f);
            cameras.push_back(inside);
            Camera clipped = lens;
            clipped.position = {bounds.min.x - 3.0f, c.y, c.z};
            clipped.target = clipped.position + glm::vec3(1.0f, 0.0f, -0.1f);
            clipped.near_plane = 3.0f + 0.5f * (skin.min.x - bounds.min.x);
            cameras.push_back(clipped);
            break;
        }
    }
    return cameras;
}

}  // namespace

TEST(ShadowCulling, FramesEqualUnculledFramesWhereSkinsWouldSeeThrough)
{
    SmallCity small(3, 128, 128);
    const SkinOccluders skins(small.scene, "", 8);
    ASSERT_GT(skins.size(), 20u);

    std::vector<Camera> cameras = through_the_mesh_cameras(small.scene, skins.boxes(), 12);
    ASSERT_GE(cameras.size(), 16u);
    // The premise: each of these eyes is inside the bounds of a mesh that
    // holds a skin, or its near plane reaches into them.
    for (const Camera &camera : cameras) {
        bool premise = false;
        for (const Mesh &m : small.scene.meshes) {
            Aabb bounds;
            for (const glm::vec3 &p : m.positions)
                bounds.expand(p);
            const glm::vec3 d = glm::max(glm::max(bounds.min - camera.position, camera.position - bounds.max), glm::vec3(0.0f));
            premise = premise || glm::length(d) < camera.near_plane;
        }
        ASSERT_TRUE(premise);
    }
    const std::size_t awkward = cameras.size();
    for (const Camera &c : small.setup.route("random:40:11", 40))
        cameras.push_back(c);
    for (const Camera &c : small.setup.route("dense", 8))
        cameras.push_back(c);

    // Every conservative strategy and test variant whose occluders are
    // skins (the families that read a skin database).
    MeasurementSession session(small.setup, small.ctx, checking_session_options());
    std::vector<StrategyTestVariant> with_skins;
    for (const StrategyTestVariant &v : conservative_test_variants()) {
        const auto read = databases_read(choose_strategy(v.spec));
        if (std::any_of(read.begin(), read.end(), [](const DatabaseNeed *d) { return d->setting == "skin-database"; })) {
            with_skins.push_back(v);
            add_variant(session, v);
        }
    }
    ASSERT_GE(with_skins.size(), 10u);
    add_variant(session, StrategyTestVariant("none"));   // what shadow's share culled is of
    std::map<std::string, std::vector<std::vector<std::uint32_t>>> leaves;
    for (std::size_t f = 0; f < cameras.size(); ++f)
        session.measure(f, cameras[f], [&](const SessionStrategy &s, const StrategyFrame &frame) {
            EXPECT_EQ(differing_pixels(frame), 0u)
                << s.label << ", camera " << f << (f < awkward ? " (through a mesh)" : "");
            leaves[s.label].push_back(frame.stats.drawn);
        });
    std::map<std::string, double> drawn;
    for (const SessionStrategy &s : session.strategies())
        drawn[s.label] = s.measured.triangles;
    EXPECT_GT(expect_declared_bounds(session, with_skins), 0u);

    EXPECT_LT(drawn["shadow/16"], drawn["none/16"] * 3 / 4)
        << "shadow culled too little for the comparison to mean anything";
    EXPECT_LE(drawn["shadow/16"], drawn["shadow-faces/16"]) << "aggregates hide what their faces hide";
    // Coorg and Teller's test and Hudson et al.'s agree, with the cache or without.
    for (const char *label : {"shadow/16", "planes/16", "shadow-faces/16", "planes-faces/16", "planes:plane-cache=off/16"})
        ASSERT_EQ(leaves[label].size(), cameras.size()) << label;
    for (std::size_t f = 0; f < cameras.size(); ++f) {
        EXPECT_EQ(leaves["shadow/16"][f], leaves["planes/16"][f]) << "shadow and planes, camera " << f;
        EXPECT_EQ(leaves["shadow-faces/16"][f], leaves["planes-faces/16"][f]) << "shadow-faces and planes-faces, camera " << f;
        EXPECT_EQ(leaves["planes/16"][f], leaves["planes:plane-cache=off/16"][f])
            << "planes with and without its cache, camera " << f;
    }
}
