// SPDX-License-Identifier: MIT
// Ray casting through verbose occlusion lists (Bartz et al. 1998, section
// 5; applications/ray_casting.h, volume/density_volume.h): the volume's
// trilinear density, its bricks against brute-force sampling, the ray
// marcher against the closed form of a uniform slab, and on small frames
// of a small city the image cast through the listed pixels against the
// image cast through every pixel, pixel for pixel, from views where the
// plume is hidden, seen, entered and crossed by the near plane.
#include "applications/ray_casting.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "gl/offscreen_context.h"
#include "scene/city.h"

using namespace occu;

namespace {

DensityVolume uniform_volume(float density)
{
    DensityVolume v(Aabb{{0, 0, 0}, {10, 10, 10}}, {3, 3, 3});
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i)
                v.set(i, j, k, density);
    return v;
}

}  // namespace

TEST(DensityVolume, IsTrilinearBetweenItsPointsAndZeroOutside)
{
    DensityVolume v(Aabb{{0, 0, 0}, {2, 2, 2}}, {3, 3, 3});
    v.set(1, 1, 1, 1.0f);
    EXPECT_DOUBLE_EQ(v.sample({1, 1, 1}), 1.0);
    EXPECT_DOUBLE_EQ(v.sample({0.5, 1, 1}), 0.5);
    EXPECT_DOUBLE_EQ(v.sample({0.5, 0.5, 0.5}), 0.125);
    EXPECT_DOUBLE_EQ(v.sample({1.5, 1.5, 1.0}), 0.25);
    EXPECT_DOUBLE_EQ(v.sample({0, 0, 0}), 0.0);
    EXPECT_DOUBLE_EQ(v.sample({-0.01, 1, 1}), 0.0);
    EXPECT_DOUBLE_EQ(v.sample({1, 2.01, 1}), 0.0);
}

TEST(DensityVolume, RefusesBadDensitiesAndGrids)
{
    DensityVolume v(Aabb{{0, 0, 0}, {1, 1, 1}}, {2, 2, 2});
    EXPECT_THROW(v.set(0, 0, 0, std::numeric_limits<float>::quiet_NaN()), std::invalid_argument);
    EXPECT_THROW(v.set(0, 0, 0, std::numeric_limits<float>::infinity()), std::invalid_argument);
    EXPECT_THROW(v.set(0, 0, 0, -1.0f), std::invalid_argument);
    EXPECT_EQ(v.at(0, 0, 0), 0.0f) << "a refused density changes nothing";
    EXPECT_THROW(DensityVolume(Aabb{{0, 0, 0}, {1, 1, 1}}, {1, 2, 2}), std::invalid_argument);
    EXPECT_THROW(DensityVolume(Aabb{}, {2, 2, 2}), std::invalid_argument);
    EXPECT_THROW(DensityVolume(Aabb{{0, 0, 0}, {std::numeric_limits<float>::infinity(), 1, 1}}, {2, 2, 2}),
                 std::invalid_argument);
    EXPECT_THROW(make_bricks(v, 0), std::invalid_argument);
}

// Brute force: every point with density > 0 lies in a non-empty brick, and
// no point of an empty brick has density > 0, for brick sizes that divide
// the grid and sizes that leave smaller bricks at its far faces.
TEST(Bricks, NonEmptyOnesHoldAllTheDensity)
{
    const DensityVolume v = smoke_above_block(0, 0, 80.0f, 4.0f);   // 32 x 32 x 16 cells
    std::mt19937 rng(7);
    const Aabb box = v.box();
    std::uniform_real_distribution<double> ux(box.min.x, box.max.x), uy(box.min.y, box.max.y), uz(box.min.z, box.max.z);
    std::vector<glm::dvec3> points(20000);
    for (glm::dvec3 &p : points)
        p = {ux(rng), uy(rng), uz(rng)};
    for (int cells : {1, 3, 8, 20, 32}) {
        const std::vector<Brick> bricks = make_bricks(v, cells);
        const glm::ivec3 n = v.cells();
        EXPECT_EQ(bricks.size(), std::size_t(((n.x + cells - 1) / cells) * ((n.y + cells - 1) / cells) *
                                             ((n.z + cells - 1) / cells)))
            << cells;
        std::size_t non_empty = 0, dense_points = 0;
        for (const Brick &b : bricks)
            non_empty += !b.empty;
        EXPECT_GT(non_empty, 0u);
        if (cells < 20)
            EXPECT_LT(non_empty, bricks.size()) << cells << "-cell bricks: the plume leaves some empty";
        for (const glm::dvec3 &p : points) {
            const double rho = v.sample(p);
            bool in_non_empty = false;
            for (const Brick &b : bricks) {
                const bool inside = b.box.contains(glm::vec3(p));
                if (inside && b.empty)
                    EXPECT_EQ(v.sample(glm::dvec3(glm::vec3(p))), 0.0) << "empty brick with density inside";
                in_non_empty |= inside && !b.empty;
            }
            if (rho > 0.0) {
                ++dense_points;
                EXPECT_TRUE(in_non_empty) << "density " << rho << " outside every non-empty " << cells << "-cell brick";
            }
        }
        EXPECT_GT(dense_points, 100u);
    }
}

// A uniform slab: N samples 0.5 m apart over the ray's L = 10 m inside it,
// transmittance exp(-absorption * rho * N * step), N within one of L / step.
TEST(VolumeRayCaster, MatchesAUniformSlabsTransmittance)
{
    const DensityVolume v = uniform_volume(0.2f);
    RayMarchSettings s;
    s.step = 0.5;
    s.absorption = 0.3;
    s.low_colour = s.high_colour = {0.0, 0.0, 0.0};   // black smoke: the colour is the background times T
    s.opaque = 0.0;
    VolumeRayCaster caster(v, s);
    Camera c;
    c.position = {5, 5, 20};
    c.target = {5, 5, 0};
    c.near_plane = 1.0f;
    c.far_plane = 100.0f;
    caster.set_view(c, 1, 1);   // one pixel, its ray straight down the axis
    const std::uint8_t white[3] = {255, 255, 255};
    const VolumeRayCaster::Result r = caster.cast(0, 0, white, 1.0);
    ASSERT_TRUE(r.volume_contributes);
    const double lo = std::exp(-0.3 * 0.2 * 21 * 0.5) * 255.0, hi = std::exp(-0.3 * 0.2 * 19 * 0.5) * 255.0;
    EXPECT_GE(r.rgb[0], std::floor(lo));
    EXPECT_LE(r.rgb[0], std::ceil(hi));
    EXPECT_TRUE(caster.meets_box(0, 0, 1.0));

    // A polygon in front of the slab (window depth of view depth 5 m) stops
    // the ray before it: nothing gained, the polygon's colour unchanged.
    const glm::vec4 clip = c.projection() * glm::vec4(0, 0, -5.0f, 1);
    const double window = 0.5 * double(clip.z / clip.w) + 0.5;
    const VolumeRayCaster::Result blocked = caster.cast(0, 0, white, window);
    EXPECT_FALSE(blocked.volume_contributes);
    EXPECT_EQ(blocked.rgb[0], 255);
    EXPECT_FALSE(caster.meets_box(0, 0, window));

    RayMarchSettings bad;
    bad.step = 0.0;
    EXPECT_THROW(VolumeRayCaster(v, bad), std::invalid_argument);
    bad.step = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(VolumeRayCaster(v, bad), std::invalid_argument);
}

namespace {

constexpr int view = 96;

// A 3 x 3-block city with the plume over its middle block on a grid of 2 m
// cells: the image through the listed pixels must be the image through
// every pixel.
struct MixedScene {
    gl::OffscreenContext ctx{view, view};
    CityOptions city;
    Scene scene;
    std::optional<Hierarchy> hierarchy;
    std::optional<SceneRenderer> renderer;
    DensityVolume volume = smoke_above_block(1, 1, 80.0f, 2.0f);

    MixedScene()
    {
        city.blocks_x = city.blocks_z = 3;
        scene = generate_city(city);
        hierarchy.emplace(Hierarchy::build(scene, HierarchyOptions{}));
        renderer.emplace(scene, *hierarchy);
        glViewport(0, 0, view, view);
    }

    struct Outcome {
        OcclusionRayCastingStats stats;
        std::size_t box_rays = 0, contributing = 0, differing = 0, unlisted = 0;
    };

    Outcome cast(const Camera &camera, const OcclusionRayCastingSettings &settings)
    {
        draw_polygons(*renderer, *hierarchy, camera);
        glFinish();
        const std::vector<double> depth = read_window_depth(view, view);
        const std::size_t n = std::size_t(view) * view;
        std::vector<std::uint8_t> frame(ctx.pixels(), ctx.pixels() + 4 * n), listed(4 * n), every(4 * n), contributes;
        OcclusionRayCasting lists(volume, settings);
        const std::vector<std::uint8_t> &mask = lists.pixels_to_cast(camera, view, view);
        VolumeRayCaster caster(volume, RayMarchSettings{});
        caster.set_view(camera, view, view);
        composite_volume(caster, view, view, frame.data(), depth, mask.data(), listed.data());
        const CompositeStats all = composite_volume(caster, view, view, frame.data(), depth, nullptr, every.data(), &contributes);
        Outcome o;
        o.stats = lists.stats();
        o.contributing = all.contributing;
        for (std::size_t i = 0; i < n; ++i) {
            o.differing += listed[4 * i] != every[4 * i] || listed[4 * i + 1] != every[4 * i + 1] ||
                           listed[4 * i + 2] != every[4 * i + 2];
            o.unlisted += contributes[i] && !mask[i];
            o.box_rays += caster.meets_box(int(i % view), int(i / view), depth[i]);
        }
        return o;
    }
};

Camera looking(glm::vec3 from, glm::vec3 at, float near_plane = 0.5f)
{
    Camera c;
    c.position = from;
    c.target = at;
    c.near_plane = near_plane;
    c.far_plane = 2000.0f;
    return c;
}

// The plume rises from (120, 0, 120), the middle block's courtyard, and
// drifts east (+x) to about 175 m at 120 m up.
const glm::vec3 plume_middle{140.0f, 50.0f, 120.0f};

}  // namespace

TEST(OcclusionRayCasting, AerialViewEqualsCastingEveryPixel)
{
    MixedScene s;
    for (int bricks : {2, 8, 64}) {
        OcclusionRayCastingSettings settings;
        settings.brick_cells = bricks;
        const auto o = s.cast(looking({-60, 160, -80}, plume_middle), settings);
        SCOPED_TRACE("bricks of " + std::to_string(bricks) + " cells");
        EXPECT_GT(o.contributing, 200u) << "the plume is in view";
        EXPECT_EQ(o.differing, 0u);
        EXPECT_EQ(o.unlisted, 0u);
        EXPECT_FALSE(o.stats.whole_frame);
        EXPECT_LT(o.stats.listed_pixels, std::size_t(view) * view / 2) << "the lists name the plume's pixels, not the frame";
        EXPECT_GE(o.stats.listed_pixels, o.contributing);
    }
}

// From the street the buildings of the block hide the plume's base: rays
// that meet the volume's box there stop at a facade first, and the lists
// leave them out.
TEST(OcclusionRayCasting, StreetViewSavesRaysTheBuildingsHide)
{
    MixedScene s;
    const auto o = s.cast(looking({20, 1.7f, 80}, {130, 30, 120}), OcclusionRayCastingSettings{});
    EXPECT_EQ(o.differing, 0u);
    EXPECT_EQ(o.unlisted, 0u);
    EXPECT_GT(o.contributing, 50u) << "the plume shows above the rooftops";
    EXPECT_LT(o.stats.listed_pixels, o.box_rays) << "occluded parts of the volume's box are not listed";
}

// Tiny lists overflow: their tiles fall back to the extents rectangle,
// which still holds every pixel the volume shows in.
TEST(OcclusionRayCasting, OverflowedListsFallBackToTheExtents)
{
    MixedScene s;
    OcclusionRayCastingSettings settings;
    settings.brick_cells = 2;
    settings.list_layers = 1;
    settings.tile_pixels = 16;
    const auto o = s.cast(looking({-60, 160, -80}, plume_middle), settings);
    EXPECT_GT(o.stats.tiles_overflowed, 0u) << "one pair per pixel cannot hold bricks seen behind bricks";
    EXPECT_EQ(o.differing, 0u);
    EXPECT_EQ(o.unlisted, 0u);
}

// The eye inside the plume, and the near plane across a brick: no front
// faces to test, the whole frame is cast (and still equals itself).
TEST(OcclusionRayCasting, EyeInsideTheVolumeCastsTheWholeFrame)
{
    MixedScene s;
    const auto inside = s.cast(looking({125, 40, 120}, {125, 80, 121}), OcclusionRayCastingSettings{});
    EXPECT_TRUE(inside.stats.whole_frame);
    EXPECT_EQ(inside.stats.listed_pixels, std::size_t(view) * view);
    EXPECT_GT(inside.contributing, 1000u);
    EXPECT_EQ(inside.differing, 0u);
}

// Looking away from the plume (it is behind the eye): nothing drawn, no ray cast.
TEST(OcclusionRayCasting, PlumeBehindTheEyeCastsNothing)
{
    MixedScene s;
    const auto o = s.cast(looking({120, 60, 40}, {120, 60, -100}), OcclusionRayCastingSettings{});
    EXPECT_FALSE(o.stats.whole_frame);
    EXPECT_EQ(o.stats.bricks_drawn, 0u);
    EXPECT_EQ(o.stats.listed_pixels, 0u);
    EXPECT_EQ(o.contributing, 0u);
}
