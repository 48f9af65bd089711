// SPDX-License-Identifier: MIT
// The database format every database shares (culling/database_file.h):
// the writer's header and provenance read back as written; every malformed
// header and provenance line, every bad field of a payload record, a file
// cut short and what follows its end are refused naming the file and the
// line; NaN and infinity are refused in fields and settings; the
// provenance's key and difference see every record; a database serves only
// its scene and, when made with one, its Mesa.
#include "culling/database_file.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

using namespace occu;

namespace {

std::string temp_file(const std::string &name, const std::string &text)
{
    const std::string path = ::testing::TempDir() + "occu-dbfile-" + std::to_string(getpid()) + "-" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

const std::string provenance_lines = "algorithm counting\n"
                                     "settings size=3 grid=1,2.5,-4\n"
                                     "scene 0123456789abcdef leaves=10 triangles=99\n"
                                     "code 0123456789ab\n"
                                     "mesa none\n";
const std::string header = "occu-database table 2\n" + provenance_lines;   // the payload starts at line 7

// What reading `text` as a table (version 2) throws, with every record's
// fields read by `read` (nothing when not given); empty when nothing.
std::string error_of(const std::string &name, const std::string &text,
                     const std::function<void(DatabaseReader &)> &read = {})
{
    const std::string path = temp_file(name, text);
    try {
        DatabaseReader in(path, "table", 2, "table");
        while (in.next())
            if (read)
                read(in);
        return "";
    } catch (const std::runtime_error &e) {
        const std::string message = e.what();
        return message.rfind(path, 0) == 0 ? "FILE" + message.substr(path.size()) : "not named: " + message;
    }
}

DatabaseProvenance sample_provenance()
{
    return {"counting", "size=3 grid=1,2.5,-4", "0123456789abcdef leaves=10 triangles=99", "0123456789ab", "none"};
}

}  // namespace

TEST(DatabaseFile, WhatIsWrittenReadsBack)
{
    const std::string path = ::testing::TempDir() + "occu-dbfile-roundtrip-" + std::to_string(getpid());
    const DatabaseProvenance p = sample_provenance();
    DatabaseWriter out(path, "table", 2, p);
    const double third = 1.0 / 3.0;
    const float tenth = 0.1f;
    out.out() << "row 7 " << exact_number(third) << ' ' << exact_number(tenth) << " a rest  of words\n";
    out.finish();

    DatabaseReader in(path, "table", 2, "table");
    EXPECT_EQ(in.kind(), "table");
    EXPECT_TRUE(in.provenance() == p) << in.provenance().difference(p);
    EXPECT_EQ(in.setting("size", 0, 10), 3.0);
    EXPECT_EQ(in.setting("grid", 3, -10, 10), (std::vector<double>{1.0, 2.5, -4.0}));
    EXPECT_EQ(in.scene_number("leaves", 0, 1e9), 10.0);
    ASSERT_TRUE(in.next());
    EXPECT_EQ(in.record(), "row");
    EXPECT_EQ(in.line(), 7u);
    EXPECT_EQ(in.count("n", 10), 7u);
    EXPECT_EQ(in.number("third"), third) << "written exactly";
    EXPECT_EQ(in.float_number("tenth"), tenth) << "written exactly";
    EXPECT_EQ(in.rest(), "a rest  of words");
    in.done();
    EXPECT_FALSE(in.next()) << "the end record";

    // An empty settings record reads back empty.
    DatabaseProvenance none = p;
    none.settings.clear();
    DatabaseWriter(path, "table", 2, none).finish();
    EXPECT_EQ(DatabaseReader(path, "table", 2, "table").provenance().settings, "");
}

TEST(DatabaseFile, WriterRefusesProvenanceThatWouldNotReadBack)
{
    const std::string path = ::testing::TempDir() + "occu-dbfile-refused-" + std::to_string(getpid());
    const std::pair<std::string DatabaseProvenance::*, std::string> bad[] = {
        {&DatabaseProvenance::algorithm, "two words"}, {&DatabaseProvenance::algorithm, ""},
        {&DatabaseProvenance::settings, "a=1 # b"},    {&DatabaseProvenance::settings, " a=1"},
        {&DatabaseProvenance::scene, "f\nend"},        {&DatabaseProvenance::scene, ""},
        {&DatabaseProvenance::code, "c d"},            {&DatabaseProvenance::mesa, "22.3.6\t"}};
    for (const auto &[field, text] : bad) {
        DatabaseProvenance p = sample_provenance();
        p.*field = text;
        EXPECT_THROW(DatabaseWriter(path, "table", 2, p), std::invalid_argument) << "'" << text << "'";
    }
    EXPECT_THROW(DatabaseWriter("/nonexistent-dir/x.db", "table", 2, sample_provenance()), std::runtime_error);
}

TEST(DatabaseFile, MalformedHeaderAndProvenanceNameFileAndLine)
{
    struct Case {
        std::string name, text, expect;
    } cases[] = {
        {"empty", "", "FILE: empty file, not an occu table"},
        {"comments-only", "# nothing\n\n  \n", "FILE: empty file"},
        {"not-ours", "hello world\n", "FILE:1: not an occu table (expected 'occu-database table 2')"},
        {"old-format", "# made long ago\noccu-pvs-database 1\n", "FILE:2: 'occu-pvs-database' is the format before occu-database"},
        {"other-kind", "occu-database chairs 2\n", "FILE:1: a database of chairs, not an occu table"},
        {"no-kind", "occu-database\n", "FILE:1: occu-database: the kind missing"},
        {"no-version", "occu-database table\n", "FILE:1: occu-database: the version missing"},
        {"bad-version", "occu-database table two\n", "FILE:1: occu-database: the version is 'two', not a whole number"},
        {"other-version", "occu-database table 3\n", "FILE:1: table version 3, this program reads version 2"},
        {"header-extra", "occu-database table 2 more\n", "FILE:1: occu-database: more fields than it takes ('more')"},
        {"header-only", "occu-database table 2\n", "FILE:2: ends before its algorithm record"},
        {"no-algorithm", "occu-database table 2\nsettings a=1\n", "FILE:2: expected the algorithm record here"},
        {"algorithm-empty", "occu-database table 2\nalgorithm\n", "FILE:2: algorithm: the algorithm missing"},
        {"algorithm-two", "occu-database table 2\nalgorithm a b\n", "FILE:2: algorithm: more fields than it takes ('b')"},
        {"settings-missing", "occu-database table 2\nalgorithm a\nscene f\n", "FILE:3: expected the settings record"},
        {"scene-empty", "occu-database table 2\nalgorithm a\nsettings\nscene   # nothing\ncode c\nmesa m\nend\n",
         "FILE:4: scene: what the table was made for missing"},
        {"order", "occu-database table 2\nalgorithm a\nsettings\nscene f\nmesa m\ncode c\nend\n",
         "FILE:5: expected the code record here (the provenance: algorithm, settings, scene, code, mesa), got 'mesa'"},
        {"cut-in-provenance", "occu-database table 2\nalgorithm a\nsettings\nscene f\ncode c\n",
         "FILE:6: ends before its mesa record"},
        {"mesa-two", "occu-database table 2\nalgorithm a\nsettings\nscene f\ncode c\nmesa m n\n",
         "FILE:6: mesa: more fields than it takes ('n')"},
        {"no-end", header, "FILE:7: ends before its end record (the file was cut short)"},
        {"cut-payload", header + "row 1\nrow 2\nro", "FILE:10: ends before its end record"},
        {"after-end", header + "row 1\nend\n\n# fine\nrow 2\n", "FILE:11: 'row' after the end record (line 8)"},
        {"end-extra", header + "end now\n", "FILE:7: end: more fields than it takes ('now')"},
    };
    for (const Case &c : cases)
        EXPECT_EQ(error_of(c.name, c.text).substr(0, c.expect.size()), c.expect) << c.name;
    // Blank lines, comments, CR line ends, and an end without a line break are fine.
    EXPECT_EQ(error_of("fine", "\r\n# a comment\n" + header + "row 1  # one\r\n\nend"), "");
    EXPECT_NE(error_of("missing", "").find("FILE: empty"), std::string::npos);
    const std::string nowhere = ::testing::TempDir() + "occu-no-such-database";
    try {
        DatabaseReader(nowhere, "table", 2, "table");
        ADD_FAILURE() << "read a file that is not there";
    } catch (const std::runtime_error &e) {
        EXPECT_EQ(std::string(e.what()), nowhere + ": cannot open table");
    }
}

TEST(DatabaseFile, FieldsAreCheckedAndNamedWithTheirLine)
{
    auto number = [](DatabaseReader &in) { in.number("the x"); };
    auto float_number = [](DatabaseReader &in) { in.float_number("the y"); };
    auto count = [](DatabaseReader &in) { in.count("the n", 100); };
    auto word_then_done = [](DatabaseReader &in) {
        in.word("the name");
        in.done();
    };
    struct Case {
        std::string name, payload;
        std::function<void(DatabaseReader &)> read;
        std::string expect;
    } cases[] = {
        {"nan", "row nan\n", number, "FILE:7: row: the x is 'nan', not a finite number"},
        {"NaN", "row 1\nrow NaN\n", number, "FILE:8: row: the x is 'NaN', not a finite number"},
        {"inf", "row inf\n", number, "FILE:7: row: the x is 'inf', not a finite number"},
        {"minus-infinity", "row -infinity\n", number, "FILE:7: row: the x is '-infinity', not a finite number"},
        {"huge", "row 1e400\n", number, "FILE:7: row: the x is '1e400', not a finite number"},
        {"text", "row one\n", number, "FILE:7: row: the x is 'one', not a number"},
        {"trailing", "row 1.5x\n", number, "FILE:7: row: the x is '1.5x', not a number"},
        {"missing", "row\n", number, "FILE:7: row: the x missing"},
        {"float-range", "row 1e39\n", float_number, "FILE:7: row: the y is '1e39', not a finite number in float range"},
        {"float-nan", "row -nan\n", float_number, "FILE:7: row: the y is '-nan', not a finite number in float range"},
        {"negative", "row -1\n", count, "FILE:7: row: the n is '-1', not a whole number from 0 to 100"},
        {"fraction", "row 1.5\n", count, "FILE:7: row: the n is '1.5', not a whole number"},
        {"too-many", "row 101\n", count, "FILE:7: row: the n is 101, more than 100"},
        {"overflow", "row 99999999999999999999999\n", count, "FILE:7: row: the n is '99999999999999999999999', not a whole number"},
        {"extra", "row a b\n", word_then_done, "FILE:7: row: more fields than it takes ('b')"},
    };
    for (const Case &c : cases)
        EXPECT_EQ(error_of(c.name, header + c.payload + "end\n", c.read).substr(0, c.expect.size()), c.expect)
            << c.name;
    EXPECT_EQ(error_of("good-fields", header + "row -2.5e3\nend\n", number), "");
}

TEST(DatabaseFile, SettingsAreCheckedAtTheSettingsLine)
{
    const std::string path = temp_file("settings", "occu-database table 2\nalgorithm a\n"
                                                   "settings x=nan y=1,inf z=2,3 w=7 v= u=4,,5 w=8\n"
                                                   "scene f count=-3\ncode c\nmesa m\nend\n");
    DatabaseReader in(path, "table", 2, "table");
    auto error = [&](const std::function<void()> &read) {
        try {
            read();
        } catch (const std::runtime_error &e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(error([&] { in.setting("x", -1, 1); }), path + ":3: settings: x is 'nan', not a number (finite)");
    EXPECT_EQ(error([&] { in.setting("y", 2, -1e9, 1e9); }),
              path + ":3: settings: y is '1,inf', not 2 numbers split by commas (finite)");
    EXPECT_EQ(error([&] { in.setting("z", -1e9, 1e9); }), path + ":3: settings: z is '2,3', not a number");
    EXPECT_EQ(error([&] { in.setting("w", 0, 7.5); }), path + ":3: settings: w is '8', its numbers from 0 to 7.5")
        << "the last of a key counts";
    EXPECT_EQ(error([&] { in.setting("v", 0, 1); }), path + ":3: settings: v is '', not a number (finite)");
    EXPECT_EQ(error([&] { in.setting("u", 3, 0, 9); }),
              path + ":3: settings: u is '4,,5', not 3 numbers split by commas (finite)");
    EXPECT_EQ(error([&] { in.setting("t", 0, 1); }), path + ":3: settings: t=VALUE missing (a number)");
    EXPECT_EQ(error([&] { in.scene_number("count", 0, 9); }),
              path + ":4: scene: count is '-3', its numbers from 0 to 9");
    EXPECT_EQ(error([&] { in.require_algorithm("counting"); }),
              path + ":2: algorithm 'a': this reads the table of counting");
}

TEST(DatabaseFile, ProvenanceKeyDifferenceAndMismatch)
{
    const DatabaseProvenance p = sample_provenance();
    EXPECT_EQ(p.key().size(), 16u);
    EXPECT_EQ(p.key(), sample_provenance().key());
    EXPECT_EQ(p.difference(p), "");
    for (std::string DatabaseProvenance::*field : {&DatabaseProvenance::algorithm, &DatabaseProvenance::settings,
                                                   &DatabaseProvenance::scene, &DatabaseProvenance::code,
                                                   &DatabaseProvenance::mesa}) {
        DatabaseProvenance other = p;
        other.*field += "x";
        EXPECT_NE(other.key(), p.key());
        EXPECT_FALSE(other == p);
        EXPECT_NE(other.difference(p).find("' against '"), std::string::npos) << other.difference(p);
    }
    // Records do not run into each other: moving a letter across makes another key.
    DatabaseProvenance moved = p;
    moved.algorithm = "countin";
    moved.settings = "g" + p.settings;
    EXPECT_NE(moved.key(), p.key());
    DatabaseProvenance settings = p;
    settings.settings = "size=4 grid=1,2.5,-4";
    EXPECT_EQ(settings.difference(p), "settings 'size=4 grid=1,2.5,-4' against 'size=3 grid=1,2.5,-4'");

    // The current program's provenance; serves its scene, on its Mesa.
    const DatabaseProvenance gl = DatabaseProvenance::current("a", "s=1", "scene words", true);
    EXPECT_EQ(gl.code, library_code_hash());
    EXPECT_EQ(gl.mesa, mesa_build());
    EXPECT_EQ(DatabaseProvenance::current("a", "s=1", "scene words", false).mesa, "none");
    EXPECT_EQ(gl.mismatch("scene words"), "");
    EXPECT_EQ(gl.mismatch("other words"), "made for another scene (scene words; this one is other words)");
    DatabaseProvenance old_mesa = gl;
    old_mesa.mesa = "21.0.0/install-x";
    EXPECT_NE(old_mesa.mismatch("scene words").find("made with another Mesa (21.0.0/install-x; this program runs on "),
              std::string::npos);
    DatabaseProvenance no_mesa = old_mesa;
    no_mesa.mesa = "none";
    EXPECT_EQ(no_mesa.mismatch("scene words"), "") << "made without GL: any Mesa";
    // The code hash is the build's: twelve hex digits.
    EXPECT_EQ(std::string(library_code_hash()).find_first_not_of("0123456789abcdef"), std::string::npos);
    EXPECT_EQ(std::string(library_code_hash()).size(), 12u);
}

TEST(DatabaseFile, ExactNumbersAreShortAndReadBack)
{
    EXPECT_EQ(exact_number(0.5), "0.5");
    EXPECT_EQ(exact_number(0.1f), "0.1");
    EXPECT_EQ(exact_number(24.0), "24");
    for (double v : {1.0 / 3.0, -1e-300, 6.02214076e23, std::numeric_limits<double>::max()})
        EXPECT_EQ(std::strtod(exact_number(v).c_str(), nullptr), v);
    for (float v : {1.0f / 3.0f, -1e-30f, std::numeric_limits<float>::max(), std::numeric_limits<float>::denorm_min()})
        EXPECT_EQ(std::strtof(exact_number(v).c_str(), nullptr), v);
}
