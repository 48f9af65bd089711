// SPDX-License-Identifier: MIT
// Shadow culling (Moeller and Haines, "Occlusion Culling Algorithms",
// section "Shadow Culling": `shadow`, Hudson et al.; `planes`, Coorg and
// Teller), and every other strategy whose occluders are occluder skins
// (skins, hzb, hom), where skins would hide what GL shows: the eye inside a mesh (back-face culling then shows what
// lies behind the mesh's skin) and a near plane that clips away the mesh's
// surface in front of a skin. In both the strategies must leave the skin
// out (SkinOccluders::usable), and their frames equal the unculled
// frames byte for byte, as on many random views of a small city; and the
// two families, equivalent for single convex occluders, draw the same
// leaves. Runs on the driver meson selects with GALLIUM_DRIVER.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "camera/route.h"
#include "culling/registry.h"
#include "gl/offscreen_context.h"
#include "occluders/skin_occluders.h"
#include "scene/city.h"

#include "frame_comparison.h"
#include "small_city.h"

using namespace occu;
using occu::integration::draw_frame;
using occu::integration::DrawnFrame;

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
    const integration::SmallCity small(3, 128, 128);
    const Hierarchy &h = small.h;
    const StrategyContext context{small.scene, h, small.renderer};
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

    const Strategy none = make_strategy("none", context);
    std::uint64_t drawn_none = 0;
    std::vector<std::uint64_t> drawn_by(11, 0);
    std::vector<std::vector<std::vector<std::uint32_t>>> leaves(11);
    // The shadow families first (indices used below), then every other
    // strategy whose occluders are skins.
    const std::vector<std::string> specs = {"shadow",       "planes", "shadow-faces", "planes-faces",
                                            "planes:plane-cache=off", "shadow:occluders=64",
                                            "skins", "skins:occludee=rect", "skins-both", "hzb", "hom"};
    std::vector<Strategy> strategies;
    for (const std::string &spec : specs)
        strategies.push_back(make_strategy(spec, context));
    TraversalOptions options;
    options.batch = 16;
    for (std::size_t f = 0; f < cameras.size(); ++f) {
        const Frame frame(cameras[f], 128, 128);
        const DrawnFrame reference = draw_frame(small.ctx, small.renderer, h, *none.culler, frame, {});
        drawn_none += reference.triangles;
        for (std::size_t s = 0; s < specs.size(); ++s) {
            const DrawnFrame culled = draw_frame(small.ctx, small.renderer, h, *strategies[s].culler, frame, options);
            EXPECT_TRUE(reference.pixels == culled.pixels)
                << specs[s] << ", camera " << f << (f < awkward ? " (through a mesh)" : "");
            drawn_by[s] += culled.triangles;
            leaves[s].push_back(culled.leaves);
        }
    }
    EXPECT_LT(drawn_by[0], drawn_none * 3 / 4) << "shadow culled too little for the comparison to mean anything";
    EXPECT_LE(drawn_by[0], drawn_by[2]) << "aggregates hide what their faces hide";
    EXPECT_LE(drawn_by[5], drawn_by[0]) << "more occluders hide more";
    // Coorg and Teller's test and Hudson et al.'s agree, with the cache or without.
    for (std::size_t f = 0; f < cameras.size(); ++f) {
        EXPECT_EQ(leaves[0][f], leaves[1][f]) << "shadow and planes, camera " << f;
        EXPECT_EQ(leaves[2][f], leaves[3][f]) << "shadow-faces and planes-faces, camera " << f;
        EXPECT_EQ(leaves[1][f], leaves[4][f]) << "planes with and without its cache, camera " << f;
    }
}
