// The occluder database file: what save writes, load reads back, with its
// provenance; shards merge; malformed files and files without provenance
// are refused with the file and line named; a database made for another
// scene or hierarchy is refused naming the difference; views are found by
// nearest point and heading.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "scene/scene.h"
#include "strategies/poon_wang_opacity_maps/occluder_database.h"

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
    db.provenance.code = "0123456789ab";
    db.provenance.options = "resolution=128 map-divisor=4";
    db.provenance.resolution = 128;
    db.provenance.scene = "00000000deadbeef";
    db.provenance.leaves = 100;
    db.provenance.triangles = 12345;
    db.provenance.mesa = "22.3.6/install-a-b";
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
    const auto db = sample();
    const std::string path = ::testing::TempDir() + "occu-db-roundtrip.txt";
    db.save(path);
    const auto back = OccluderDatabase::load(path);
    EXPECT_TRUE(back.grid == db.grid);
    EXPECT_TRUE(back.provenance == db.provenance);
    EXPECT_EQ(back.provenance.options, "resolution=128 map-divisor=4");
    EXPECT_EQ(back.provenance.leaves, 100u);
    EXPECT_EQ(back.provenance.triangles, 12345u);
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
    b.provenance.triangles = 1;
    EXPECT_THROW(OccluderDatabase::merge({a, b}), std::runtime_error);   // another scene
    b = sample();
    b.views.erase(0);
    b.provenance.options = "resolution=64 map-divisor=4";
    EXPECT_THROW(OccluderDatabase::merge({a, b}), std::runtime_error);   // other options
}

TEST(OccluderDatabase, KeyChangesWithEveryInput)
{
    const auto db = sample();
    const std::string key = db.provenance.key(db.grid);
    EXPECT_EQ(key.size(), 12u);
    EXPECT_EQ(key, sample().provenance.key(sample().grid));
    auto other = sample();
    other.provenance.options += " max-occluders=8";
    EXPECT_NE(other.provenance.key(other.grid), key);
    other = sample();
    other.provenance.code = "ffffffffffff";
    EXPECT_NE(other.provenance.key(other.grid), key);
    other = sample();
    other.provenance.mesa = "22.3.6/install-a-c";
    EXPECT_NE(other.provenance.key(other.grid), key);
    other = sample();
    other.grid.directions = 8;
    EXPECT_NE(other.provenance.key(other.grid), key);
}

TEST(OccluderDatabase, RefusesAnotherSceneOrMesaNamingIt)
{
    Scene scene;
    scene.meshes.emplace_back();
    append_box(scene.meshes[0], Aabb::of({0, 0, 0}, {1, 1, 1}));
    scene.update_bounds();
    const Hierarchy h = Hierarchy::build(scene);
    DatabaseProvenance p = DatabaseProvenance::current(h, "resolution=128", 128);
    EXPECT_EQ(p.mismatch_for(h), "");
    EXPECT_EQ(p.mesa, mesa_build());
    EXPECT_EQ(p.code, preprocessing_code_hash());

    append_box(scene.meshes[0], Aabb::of({2, 0, 0}, {3, 1, 1}));
    scene.update_bounds();
    const Hierarchy other = Hierarchy::build(scene);
    EXPECT_NE(other.fingerprint(), h.fingerprint());
    EXPECT_NE(p.mismatch_for(other).find("another scene or hierarchy"), std::string::npos) << p.mismatch_for(other);
    p.mesa = "21.0.0/install-x-y";
    EXPECT_NE(p.mismatch_for(h).find("another Mesa"), std::string::npos) << p.mismatch_for(h);
}

TEST(OccluderDatabase, MalformedFilesNameFileAndLine)
{
    const std::string provenance = "algorithm minimum-occluder-set 0123456789ab\noptions resolution=32\n"
                                   "resolution 32\nscene 00000000deadbeef 10 100\nmesa 22.3.6/x\n";
    const std::string header = "occu-occluder-database 2\n" + provenance + "grid 0 0 0 1 1 1 2 1 2 4\n";
    EXPECT_NE(error_of(temp_file("db-empty.txt", "")).find("empty"), std::string::npos);
    EXPECT_NE(error_of(temp_file("db-magic.txt", "hello\n")).find("db-magic.txt:1"), std::string::npos);
    EXPECT_NE(error_of(temp_file("db-range.txt", header + "view 99 1 2\n")).find("db-range.txt:8"), std::string::npos);
    EXPECT_NE(error_of(temp_file("db-id.txt", header + "view 1 1 x\n")).find("db-id.txt:8"), std::string::npos);
    EXPECT_NE(error_of(temp_file("db-twice.txt", header + "view 1 1\nview 1 2\n")).find("repeats"), std::string::npos);
    EXPECT_NE(error_of(temp_file("db-grid.txt", "occu-occluder-database 2\n" + provenance + "grid 0 0 0 1 1 1 0 1 1 4\n"))
                  .find(":7"),
              std::string::npos);
    // A database without provenance: version 1, or a record missing.
    EXPECT_NE(error_of(temp_file("db-v1.txt", "occu-occluder-database 1\ngrid 0 0 0 1 1 1 2 1 2 4\nscene 10 100\n"))
                  .find("db-v1.txt:1: made by an older occu-preprocess"),
              std::string::npos);
    EXPECT_NE(error_of(temp_file("db-no-mesa.txt", "occu-occluder-database 2\nalgorithm minimum-occluder-set c\n"
                                                   "options x\nresolution 32\nscene f 1 2\ngrid 0 0 0 1 1 1 2 1 2 4\n"))
                  .find("no mesa record"),
              std::string::npos);
    EXPECT_NE(error_of(temp_file("db-res.txt", "occu-occluder-database 2\nresolution -3\n")).find("db-res.txt:2"),
              std::string::npos);
    EXPECT_NE(error_of(::testing::TempDir() + "no-such-db.txt").find("cannot open"), std::string::npos);
    EXPECT_EQ(error_of(temp_file("db-ok.txt", header + "# a comment\nview 3 1 2 3\n")), "");
}

namespace {
const std::string provenance_records = "occu-occluder-database 2\n"
                                       "algorithm minimum-occluder-set 0123456789ab\noptions resolution=32\n"
                                       "resolution 32\nscene 00000000deadbeef 10 100\nmesa 22.3.6/x\n";
}  // namespace

TEST(OccluderDatabase, GridNumbersThatAreNotFiniteAreRefusedNamingFileLineAndNumber)
{
    // nan and inf are what strtod reads; 1e39 is beyond float range, so
    // the grid's float coordinate would be infinite.
    const std::string path_prefix = "db-not-finite-" + std::to_string(::getpid()) + "-";
    for (const std::string bad : {"nan", "-inf", "1e39"}) {
        SCOPED_TRACE(bad);
        const std::string path = temp_file(path_prefix + bad, provenance_records + "grid 0 0 0 1 " + bad + " 1 2 1 2 4\n");
        const std::string message = error_of(path);
        EXPECT_NE(message.find(path + ":7"), std::string::npos) << message;
        EXPECT_NE(message.find("SY is '" + bad + "'"), std::string::npos) << message;
        EXPECT_NE(message.find("not a finite number"), std::string::npos) << message;
    }
}

TEST(OccluderDatabase, GridWhosePointsOverflowIsRefused)
{
    // Every number is a finite float, but the fourth point along x lies at
    // 3 * 3e38: its cameras would stand at infinity.
    const std::string path = temp_file("db-overflow-" + std::to_string(::getpid()),
                                       provenance_records + "grid 0 0 0 3e38 1 1 4 1 1 4\n");
    const std::string message = error_of(path);
    EXPECT_NE(message.find(path + ":7"), std::string::npos) << message;
    EXPECT_NE(message.find("beyond float range"), std::string::npos) << message;
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
