// SPDX-License-Identifier: MIT
// View-cell visibility (Wonka, Wimmer and Schmalstieg 2000;
// strategies/wonka_view_cells/view_cell_visibility.h): on a 3x3-block city,
// the potentially visible sets found with the Occlusion Unit equal those
// found by reading the cull maps back; and the `pvs` strategy, fed a database
// of those sets, draws frames equal to unculled frames from random eyes
// anywhere in their cells (corners, edges, street level and the cells' top
// included, looking any way, straight up and down too), culls far more than
// vfc, and falls back to view-frustum culling, saying so, for eyes in no
// cell.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <set>

#include "camera/route.h"
#include "culling/registry.h"
#include "evaluation/measurement_session.h"
#include "gl/offscreen_context.h"
#include "render/scene_renderer.h"
#include "scene/city.h"
#include "strategies/wonka_view_cells/pvs_database.h"

#include "small_city.h"
#include "strategy_variants.h"

using namespace occu;
using namespace occu::integration;

namespace {

constexpr int size = 128;

// The small city of 3x3 blocks in leaves of the default size, with its view cells.
struct City : SmallCity {
    City() : SmallCity(3, 256, size)
    {
        cells.emplace(glm::dvec2(scene.bounds.min.x, scene.bounds.min.z), glm::dvec2(scene.bounds.max.x, scene.bounds.max.z),
                      scene.prism_occluders, ViewCellOptions{});
    }
    std::optional<ViewCells> cells;
};

// A point of cell c's prism: barycentric (u, v, 1 - u - v), height y.
glm::vec3 point_in(const ViewCells &cells, std::size_t c, double u, double v, double y)
{
    const auto &t = cells.triangle(c);
    const glm::dvec2 p = t[0] * u + t[1] * v + t[2] * (1.0 - u - v);
    return {float(p.x), float(y), float(p.y)};
}

}  // namespace

TEST(ViewCellFrames, PvsFramesEqualUnculledFramesFromAnywhereInTheCells)
{
    City city;
    const StrategyContext context{city.scene, city.h, city.renderer};
    ViewCellVisibility visibility(city.scene, city.h, *city.cells, ViewCellVisibilityOptions{});

    // The eyes: random points of random cells at random heights in the
    // prism, and the awkward ones: a corner at street level, an edge's
    // middle at the cell's top; random headings, and straight up and down.
    std::mt19937 rng(2000);
    std::uniform_int_distribution<std::size_t> pick(0, city.cells->size() - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Camera> cameras;
    std::set<std::uint32_t> needed;
    for (int i = 0; i < 24; ++i) {
        const std::size_t c = pick(rng);
        double u = unit(rng), v = unit(rng);
        if (u + v > 1.0)
            u = 1.0 - u, v = 1.0 - v;
        double y = unit(rng) * 2.0;
        // (Within a millimetre of them: float eye coordinates could round a
        // corner on the cells' outer boundary out of every cell.)
        if (i == 0)
            u = 1.0 - 2e-5, v = 1e-5, y = 0.0;   // a corner, at street level
        if (i == 1)
            u = 0.5 - 1e-5, v = 0.5 - 1e-5, y = 2.0;   // an edge's middle, at the top
        Camera cam;
        cam.position = point_in(*city.cells, c, u, v, y);
        const double heading = unit(rng) * 2.0 * std::acos(-1.0);
        const double pitch = i == 2 ? 1.5707 : i == 3 ? -1.5707 : (unit(rng) - 0.3) * 0.8;
        cam.target = cam.position + glm::vec3(float(std::cos(heading) * std::cos(pitch)), float(std::sin(pitch)),
                                              float(std::sin(heading) * std::cos(pitch)));
        cam.near_plane = 0.1f;
        cam.far_plane = 2000.0f;
        const std::optional<std::uint32_t> located = city.cells->locate(cam.position);
        ASSERT_TRUE(located) << "eye " << i << " is in cell " << c;
        needed.insert(*located);
        cameras.push_back(cam);
    }

    // Their cells' sets, both ways: the same leaves.
    PvsDatabase db = PvsDatabase::start(city.h, ViewCellOptions{}, ViewCellVisibilityOptions{});
    for (std::size_t c = 0; c < city.cells->size(); ++c)
        db.cells.push_back(city.cells->triangle(c));
    for (std::uint32_t c : needed) {
        const CellVisibility by_unit = visibility.compute(c, CullMapTest::occlusion_unit);
        const CellVisibility by_readback = visibility.compute(c, CullMapTest::readback);
        EXPECT_EQ(by_unit.visible_leaves, by_readback.visible_leaves) << "cell " << c;
        EXPECT_LT(by_unit.visible_leaves.size(), city.h.leaf_count()) << "cell " << c << " hides nothing";
        db.visible[c] = by_unit.visible_leaves;
    }
    const std::string path = testing::TempDir() + "/occu-view-cells-test.pvs";
    db.save(path);
    EXPECT_TRUE(PvsDatabase::load(path) == db) << "the database reads back as written";
    EXPECT_THROW(make_strategy("pvs:pvs-database=" + path + ":epsilon=2", context), std::invalid_argument)
        << "a setting the database decides, given beside it, would be ignored";

    // vfc and pvs through the measurement session: every pvs frame equals
    // the unculled frame (evaluation/lost_pixels.h).
    SessionOptions so = checking_session_options();
    MeasurementSession session(city.setup, city.ctx, so);
    const SessionStrategy &vfc = add_variant(session, StrategyTestVariant("vfc").in_batches_of(so.batch));
    const SessionStrategy &pvs =
        add_variant(session, StrategyTestVariant("pvs:pvs-database=" + path).in_batches_of(so.batch));
    const auto pvs_frames_equal_unculled = [&](const SessionStrategy &s, const StrategyFrame &f) {
        if (&s != &pvs)
            return;
        const glm::vec3 &eye = f.frame->camera.position;
        EXPECT_EQ(differing_pixels(f), 0u) << "visible leaves not drawn:" << visible_leaves_not_drawn(f) << "; eye "
                                           << f.index << " at (" << eye.x << ", " << eye.y << ", " << eye.z << ")";
    };
    for (std::size_t i = 0; i < cameras.size(); ++i)
        session.measure(i, cameras[i], pvs_frames_equal_unculled);
    // A cell's set holds whatever any eye of it sees in any direction; cut
    // by one frustum it still draws more than that eye sees (here about two
    // thirds of what vfc draws, on random views of a small city).
    EXPECT_LT(pvs.measured.triangles * 4, vfc.measured.triangles * 3)
        << "pvs culled less than a quarter of what vfc draws";
    EXPECT_EQ(pvs.strategy.culler->note().rfind("0 of 24 frames with the eye in no view cell", 0), 0u)
        << pvs.strategy.culler->note();

    // Eyes in no cell: inside a building, above the cells' tops. Drawn with
    // view-frustum culling, so equal frames, and counted in the note.
    const PrismOccluder &b = city.scene.prism_occluders.front();
    Camera inside;
    inside.position = glm::vec3(float(0.5 * (b.outline[0].x + b.outline[2].x)), 1.7f,
                                float(0.5 * (b.outline[0].y + b.outline[2].y)));
    inside.target = inside.position + glm::vec3(1, 0, 0);
    Camera above = cameras[4];
    above.position.y = 40.0f;
    std::size_t index = cameras.size();
    for (const Camera &c : {inside, above}) {
        ASSERT_FALSE(city.cells->locate(c.position));
        session.measure(index++, c, pvs_frames_equal_unculled);
    }
    EXPECT_EQ(pvs.strategy.culler->note().rfind("2 of 26 frames with the eye in no view cell", 0), 0u)
        << pvs.strategy.culler->note();
    std::filesystem::remove(path);
}

TEST(ViewCellFrames, RefusesADatabaseOfAnotherHierarchyAndScenesWithout25DOccluders)
{
    City city;
    const StrategyContext context{city.scene, city.h, city.renderer};
    PvsDatabase db = PvsDatabase::start(city.h, ViewCellOptions{}, ViewCellVisibilityOptions{});
    db.provenance.scene = "0123456789abcdef leaves=1 triangles=12";
    db.cells = {{glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(0, 1)}};
    const std::string path = testing::TempDir() + "/occu-other.pvs";
    db.save(path);
    try {
        make_strategy("pvs:pvs-database=" + path, context);
        ADD_FAILURE() << "a database of another hierarchy was taken";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find(path + ": made for another scene (0123456789abcdef leaves=1 triangles=12; "
                                             "this one is " + scene_provenance(city.h) + ")"),
                  std::string::npos)
            << e.what();
    }
    std::filesystem::remove(path);

    Scene plain = city.scene;
    plain.prism_occluders.clear();
    const Hierarchy h = Hierarchy::build(plain);
    const SceneRenderer renderer(plain, h);
    try {
        make_strategy("pvs", StrategyContext{plain, h, renderer});
        ADD_FAILURE() << "a scene without 2.5D occluders was taken";
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("2.5D occluders"), std::string::npos) << e.what();
    }
}
