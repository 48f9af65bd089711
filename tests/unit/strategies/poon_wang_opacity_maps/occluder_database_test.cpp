// SPDX-License-Identifier: MIT
// The occluder database file: what save writes, load reads back, with its
// provenance and the grid and resolution of its settings; shards merge;
// malformed payload lines and grid settings are refused with the file and
// line named (the shared header's own cases: database_file_test.cpp); a
// database made for another scene or hierarchy is refused naming the
// difference; views are found by nearest point and heading.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "scene/scene.h"
#include "strategies/poon_wang_opacity_maps/occluder_database.h"
#include "strategies/poon_wang_opacity_maps/view_preprocessing.h"

using namespace occu;

namespace {

std::string temp_file(const std::string &name, const std::string &text)
{
    const std::string path = ::testing::TempDir() + name;
    std::ofstream(path) << text;
    return path;
}

OccluderDatabase sample()
{
    OccluderDatabase db;
    db.grid.origin = {-10.0f, 1.7f, -10.0f};
    db.grid.spacing = {10.0f, 0.0f, 10.0f};
    db.grid.points = {3, 1, 3};
    db.grid.directions = 4;
    db.resolution = 128;
    db.provenance = {"minimum-occluder-set", "resolution=128 map-divisor=4 " + grid_settings(db.grid),
                     "00000000deadbeef leaves=100 triangles=12345", "0123456789ab", "22.3.6/install-a-b"};
    db.views[0] = {5, 3, 9};
    db.views[7] = {};
    db.views[35] = {1};
    return db;
}

std::string error_of(const std::string &path)
{
    try {
        OccluderDatabase::load(path);
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(OccluderDatabase, SaveThenLoadGivesTheSameDatabase)
{
    auto db = sample();
    // Coordinates that a decimal with few digits does not hold exactly.
    db.grid.origin = {-10.1f, 1.0f / 3.0f, 1e-7f};
    db.grid.spacing = {9.99f, 0.0f, 3e30f};
    db.provenance.settings = "resolution=128 map-divisor=4 " + grid_settings(db.grid);
    const std::string path = ::testing::TempDir() + "occu-db-roundtrip.txt";
    db.save(path);
    const auto back = OccluderDatabase::load(path);
    EXPECT_TRUE(back.grid == db.grid);
    EXPECT_TRUE(back.provenance == db.provenance) << back.provenance.difference(db.provenance);
    EXPECT_EQ(back.resolution, 128);
    EXPECT_EQ(back.views, db.views);
}

TEST(OccluderDatabase, ShardsMergeAndConflictsAreRefused)
{
    auto a = sample(), b = sample();
    a.views.erase(35);
    b.views.erase(0);
    b.views.erase(7);
    const auto merged = OccluderDatabase::merge({a, b});
    EXPECT_EQ(merged.views, sample().views);
    EXPECT_THROW(OccluderDatabase::merge({a, a}), std::runtime_error);   // view 0 twice
    b.provenance.scene = "00000000deadbeef leaves=100 triangles=1";
    EXPECT_THROW(OccluderDatabase::merge({a, b}), std::runtime_error);   // another scene
    b = sample();
    b.views.erase(0);
    b.provenance.settings = "resolution=64 map-divisor=4";
    try {
        OccluderDatabase::merge({a, b});
        ADD_FAILURE() << "merged shards of other settings";
    } catch (const std::runtime_error &e) {
        EXPECT_NE(std::string(e.what()).find("shard 2 was made otherwise than the first: settings 'resolution=64"),
                  std::string::npos)
            << e.what();
    }
}

TEST(OccluderDatabase, ProvenanceOfAMakingHoldsItsGridLensAndOptions)
{
    Scene scene;
    scene.meshes.emplace_back();
    append_box(scene.meshes[0], Aabb::of({0, 0, 0}, {1, 1, 1}));
    scene.update_bounds();
    const Hierarchy h = Hierarchy::build(scene);
    const OccluderGrid grid = OccluderGrid::over_scene(scene.bounds, {2, 1, 2}, 4, 1.7f);
    const Camera lens;
    PreprocessOptions options;
    const OccluderDatabase db = occluder_database_for(h, grid, lens, options);
    EXPECT_EQ(db.provenance.algorithm, "minimum-occluder-set");
    EXPECT_EQ(db.provenance.code, library_code_hash());
    EXPECT_EQ(db.provenance.mesa, mesa_build());
    EXPECT_EQ(db.provenance.scene, scene_provenance(h));
    EXPECT_EQ(db.resolution, options.stacks.resolution);
    EXPECT_NE(db.provenance.settings.find(options.describe()), std::string::npos);
    EXPECT_NE(db.provenance.settings.find(grid_settings(grid)), std::string::npos);
    // Each input names another database.
    const std::string key = db.provenance.key();
    EXPECT_EQ(occluder_database_for(h, grid, lens, options).provenance.key(), key);
    OccluderGrid higher = grid;
    higher.origin.y += 0.5f;
    EXPECT_NE(occluder_database_for(h, higher, lens, options).provenance.key(), key);
    Camera wider = lens;
    wider.fovy_degrees = 90.0f;
    EXPECT_NE(occluder_database_for(h, grid, wider, options).provenance.key(), key);
    PreprocessOptions fewer = options;
    fewer.max_occluders = 8;
    EXPECT_NE(occluder_database_for(h, grid, lens, fewer).provenance.key(), key);

    // It serves its own scene on this Mesa, and no other.
    EXPECT_EQ(db.provenance.mismatch(scene_provenance(h)), "");
    append_box(scene.meshes[0], Aabb::of({2, 0, 0}, {3, 1, 1}));
    scene.update_bounds();
    const Hierarchy other = Hierarchy::build(scene);
    const std::string why = db.provenance.mismatch(scene_provenance(other));
    EXPECT_NE(why.find("made for another scene"), std::string::npos) << why;
    DatabaseProvenance elsewhere = db.provenance;
    elsewhere.mesa = "21.0.0/install-x-y";
    EXPECT_NE(elsewhere.mismatch(scene_provenance(h)).find("another Mesa"), std::string::npos);
}

namespace {

// The header of a database of a 2 x 1 x 2 grid of 4 headings (16 views); its payload starts at line 7.
std::string header_with(const std::string &grid)
{
    return "occu-database occluder-sets 1\nalgorithm minimum-occluder-set\nsettings resolution=32 " + grid +
           "\nscene 00000000deadbeef leaves=10 triangles=100\ncode 0123456789ab\nmesa 22.3.6/x\n";
}

const std::string good_grid = "grid-origin=0,0,0 grid-spacing=1,1,1 grid-points=2,1,2 headings=4";

}  // namespace

TEST(OccluderDatabase, MalformedFilesNameFileAndLine)
{
    const std::string header = header_with(good_grid);
    struct Case {
        std::string file, expect;
    } cases[] = {
        {header + "view 16 1 2\nend\n", ":7: view: the view is 16, more than 15"},
        {header + "view 1 1 x\nend\n", ":7: view: an occluder is 'x', not a whole number"},
        {header + "view 1 1 -2\nend\n", ":7: view: an occluder is '-2', not a whole number"},
        {header + "view 1 1 4294967296\nend\n", ":7: view: an occluder is 4294967296, more than 4294967295"},
        {header + "view 1 1\nview 1 2\nend\n", ":8: view 1 repeats"},
        {header + "grid 0 0 0 1 1 1 2 1 2 4\nend\n", ":7: unknown record 'grid'"},
        {header + "view 1 1\n", ":8: ends before its end record"},
        {header_with("grid-origin=0,0,0 grid-spacing=1,1,1 grid-points=0,1,2 headings=4") + "end\n",
         ":3: settings: grid-points is '0,1,2', its numbers from 1 to"},
        {header_with("grid-origin=0,0,0 grid-spacing=1,1,1 grid-points=2,1.5,2 headings=4") + "end\n",
         ":3: settings: grid-points wants whole numbers"},
        {header_with("grid-origin=0,0 grid-spacing=1,1,1 grid-points=2,1,2 headings=4") + "end\n",
         ":3: settings: grid-origin is '0,0', not 3 numbers"},
        {header_with("grid-spacing=1,1,1 grid-points=2,1,2 headings=4") + "end\n",
         ":3: settings: grid-origin=VALUE missing"},
        {"occu-database occluder-sets 1\nalgorithm minimum-occluder-set\nsettings " + good_grid +
             "\nscene f\ncode c\nmesa m\nend\n",
         ":3: settings: resolution=VALUE missing"},
        {"occu-database occluder-sets 1\nalgorithm occluder-skins\nsettings\nscene f\ncode c\nmesa m\nend\n",
         ":2: algorithm 'occluder-skins'"},
        {"occu-occluder-database 2\n", ":1: 'occu-occluder-database' is the format before occu-database"},
    };
    int k = 0;
    for (const Case &c : cases) {
        const std::string name = "db-bad-" + std::to_string(::getpid()) + "-" + std::to_string(k++) + ".txt";
        const std::string error = error_of(temp_file(name, c.file));
        EXPECT_NE(error.find(name + c.expect), std::string::npos) << error;
    }
    EXPECT_NE(error_of(::testing::TempDir() + "no-such-db.txt").find("cannot open"), std::string::npos);
    EXPECT_EQ(error_of(temp_file("db-ok.txt", header + "# a comment\nview 3 1 2 3\nend\n")), "");
}

TEST(OccluderDatabase, GridNumbersThatAreNotFiniteAreRefusedNamingFileLineAndNumber)
{
    // nan and inf are what strtod reads; 1e39 is beyond float range, so
    // the grid's float coordinate would be infinite.
    const std::string path_prefix = "db-not-finite-" + std::to_string(::getpid()) + "-";
    for (const std::string bad : {"nan", "-inf", "inf", "1e39", "1e400"}) {
        SCOPED_TRACE(bad);
        const std::string path = temp_file(
            path_prefix + bad,
            header_with("grid-origin=0,0,0 grid-spacing=1," + bad + ",1 grid-points=2,1,2 headings=4") + "end\n");
        const std::string message = error_of(path);
        EXPECT_NE(message.find(path + ":3: settings: grid-spacing is '1," + bad + ",1'"), std::string::npos)
            << message;
    }
}

TEST(OccluderDatabase, GridWhosePointsOverflowIsRefused)
{
    // Every number is a finite float, but the fourth point along x lies at
    // 3 * 3e38: its cameras would stand at infinity.
    const std::string path =
        temp_file("db-overflow-" + std::to_string(::getpid()),
                  header_with("grid-origin=0,0,0 grid-spacing=3e38,1,1 grid-points=4,1,1 headings=4") + "end\n");
    const std::string message = error_of(path);
    EXPECT_NE(message.find(path + ":3: settings: the grid's points reach beyond float range along x"),
              std::string::npos)
        << message;
}

TEST(OccluderDatabase, NearestViewByPointAndHeading)
{
    const auto db = sample();
    Camera c;
    c.position = {-9.0f, 1.7f, -11.0f};            // nearest point (0, 0, 0): view 0..3
    c.target = c.position + glm::vec3(1, 0, 0.1f);  // heading 0 (+x)
    EXPECT_EQ(db.grid.nearest_view(c), 0u);
    c.target = c.position + glm::vec3(0, 0, 1);     // heading 1 (+z)
    EXPECT_EQ(db.grid.nearest_view(c), 1u);
    c.target = c.position + glm::vec3(0.1f, 0, -1); // heading 3 (-z)
    EXPECT_EQ(db.grid.nearest_view(c), 3u);
    c.position = {100.0f, 1.7f, 100.0f};            // clamped to the last point (2, 0, 2): views 32..35
    c.target = c.position + glm::vec3(0.1f, 0, -1);
    EXPECT_EQ(db.grid.nearest_view(c), 35u);
    EXPECT_EQ(db.occluders_for(c), (std::vector<std::uint32_t>{1}));
    // A view never processed (point 8, heading 0): the nearest processed
    // point of that heading, point 0 (view 0).
    c.target = c.position + glm::vec3(1, 0, 0);
    EXPECT_EQ(db.occluders_for(c), (std::vector<std::uint32_t>{5, 3, 9}));
    // Between two headings: the nearest heading's list interleaved with the
    // next one's at the same point, duplicates dropped, the next one's share
    // growing with the turn.
    auto db2 = sample();
    db2.views[1] = {3, 4};
    c.position = {-10.0f, 1.7f, -10.0f};   // point 0
    c.target = c.position + glm::vec3(std::cos(glm::radians(30.0f)), 0, std::sin(glm::radians(30.0f)));
    EXPECT_EQ(db2.occluders_for(c), (std::vector<std::uint32_t>{5, 3, 9, 4}));
    c.target = c.position + glm::vec3(std::cos(glm::radians(-30.0f)), 0, std::sin(glm::radians(-30.0f)));
    EXPECT_EQ(db2.occluders_for(c), (std::vector<std::uint32_t>{5, 3, 9}));   // heading 3 never processed
    db2.views[0] = {10, 11, 12, 13, 14, 15};
    db2.views[1] = {20, 21, 22};
    c.target = c.position + glm::vec3(std::cos(glm::radians(44.0f)), 0, std::sin(glm::radians(44.0f)));
    EXPECT_EQ(db2.occluders_for(c), (std::vector<std::uint32_t>{10, 11, 20, 12, 21, 13, 22, 14, 15}));   // about 1:1
    c.target = c.position + glm::vec3(std::cos(glm::radians(10.0f)), 0, std::sin(glm::radians(10.0f)));
    EXPECT_EQ(db2.occluders_for(c), (std::vector<std::uint32_t>{10, 11, 12, 13, 14, 15, 20, 21, 22}));   // 1:8
    c.target = c.position + glm::vec3(1, 0, 0);
    EXPECT_EQ(db2.occluders_for(c), (std::vector<std::uint32_t>{10, 11, 12, 13, 14, 15, 20, 21, 22}));   // on heading 0
    // The view camera looks along its heading from its point.
    const Camera v = db.grid.view_camera(7, c);
    EXPECT_FLOAT_EQ(v.position.x, 0.0f);
    EXPECT_NEAR(v.target.x - v.position.x, 0.0f, 1e-6f);
    EXPECT_NEAR(v.target.z - v.position.z, -1.0f, 1e-6f);
}
