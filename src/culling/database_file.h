// SPDX-License-Identifier: MIT
// The one file format of occu's databases (the minimum occluder sets of
// Poon and Wang, the occluder skins of Leone et al., the potentially visible
// sets of Wonka et al.): text, one record a line, '#' starting a comment,
// blank lines ignored. Every database opens with the same provenance
// records and closes with `end`; between them each kind has its own
// payload records:
//
//   occu-database KIND VERSION   what the payload is (its records' kind and version)
//   algorithm NAME               the algorithm that made it
//   settings KEY=VALUE ...       the settings it was made with (may be none)
//   scene FINGERPRINT ...        what it was made for (the scene, or its hierarchy)
//   code HASH                    the library's code hash (library_code_hash)
//   mesa BUILD                   the Mesa build whose Occlusion Unit made it; 'none' when made without GL
//   ...                          the payload
//   end                          the last record: a file without it was cut short
//
// DatabaseWriter writes one, DatabaseReader reads one; every error the
// reader throws names the file and line ("FILE:LINE: what"), and a number
// field is a finite number or refused (never NaN or infinity).
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace occu {

class Hierarchy;

// The hash of every source compiled into the library and the Mesa build it
// runs on (both set by the build, src/meson.build).
const char *library_code_hash();
const char *mesa_build();

// What a database was made from, by and for. Two databases of one
// provenance are the same database (DatabaseProvider names them by key()).
struct DatabaseProvenance {
    std::string algorithm;
    std::string settings;   // "key=value ..." in the order the algorithm gives them
    std::string scene;      // what the database serves: scene_provenance(hierarchy), or the algorithm's own words
    std::string code;       // library_code_hash() of the program that made it
    std::string mesa;       // mesa_build() of that program, or "none"

    // For a database this program is about to make: this library's code,
    // and this Mesa when `made_with_mesa` (the Occlusion Unit or GL drew it).
    static DatabaseProvenance current(std::string algorithm, std::string settings, std::string scene,
                                      bool made_with_mesa);
    // Why the database cannot serve a scene of provenance `scene` on this
    // program's Mesa (when it was made with one); empty when it can.
    std::string mismatch(const std::string &scene) const;
    // The first record that differs from `other`, both values named
    // ("settings 'voxel=1' against 'voxel=0.5'"); empty when none does.
    std::string difference(const DatabaseProvenance &other) const;
    // 16 hex digits hashing all of it: a file name.
    std::string key() const;
    bool operator==(const DatabaseProvenance &o) const { return difference(o).empty(); }
};

// A hierarchy's scene words: "FINGERPRINT leaves=N triangles=T"
// (Hierarchy::fingerprint covers the scene's geometry and the hierarchy).
std::string scene_provenance(const Hierarchy &hierarchy);

// A number as the shortest text that reads back to the same value.
std::string exact_number(double value);
std::string exact_number(float value);

class DatabaseWriter {
public:
    // Opens `path` and writes the header and the provenance records.
    // Throws std::runtime_error naming the file when it cannot, and
    // std::invalid_argument when a provenance field would not read back
    // (a line break or '#' in it, white space around it, or a word with spaces).
    DatabaseWriter(const std::string &path, const std::string &kind, int version, const DatabaseProvenance &provenance);
    // Payload records, each a line ended by '\n'.
    std::ostream &out() { return out_; }
    // Writes `end` and flushes; throws std::runtime_error naming the file.
    void finish();

private:
    std::string path_;
    std::ofstream out_;
};

class DatabaseReader {
public:
    // Opens `path` and reads its header and provenance records: a
    // database of `kind` ("occu-database KIND VERSION") at `version`
    // (an empty `kind`: of any kind and version, for its provenance).
    // `what` names it in messages ("occluder database"). Throws
    // std::runtime_error "PATH:LINE: ..." (or "PATH: ..." when it cannot
    // be opened or is empty).
    DatabaseReader(const std::string &path, const std::string &kind, int version, const std::string &what);

    const std::string &path() const { return path_; }
    const std::string &kind() const { return kind_; }
    const DatabaseProvenance &provenance() const { return provenance_; }
    // Refuses (at the algorithm record) a database another algorithm made.
    void require_algorithm(const std::string &algorithm) const;

    // The next payload record; false at `end` (after which only blank
    // lines and comments may follow). Throws when the file ends first.
    bool next();
    const std::string &record() const { return record_; }
    std::size_t line() const { return line_; }

    // The current record's fields, left to right; each throws naming the
    // field when it is missing or not what it should be.
    bool more() const { return field_ < fields_.size(); }
    std::string word(const std::string &what);
    // The rest of the line, white space around it dropped; empty allowed.
    std::string rest();
    // A finite number; a finite number in float range.
    double number(const std::string &what);
    float float_number(const std::string &what);
    // A whole number from 0 to `max`.
    std::uint64_t count(const std::string &what, std::uint64_t max);
    // Throws when the record has fields left.
    void done() const;

    // A setting of the provenance ("KEY=A,B,C"): its `count` numbers, each
    // finite and from `min` to `max`; throws at the settings record when it
    // is missing or another count, or a number is not one or out of range.
    std::vector<double> setting(const std::string &key, std::size_t count, double min, double max) const;
    double setting(const std::string &key, double min, double max) const { return setting(key, 1, min, max)[0]; }
    std::size_t settings_line() const { return settings_line_; }
    // The same of the scene's words ("meshes=589" of "FINGERPRINT meshes=589 ...").
    double scene_number(const std::string &key, double min, double max) const;

    [[noreturn]] void fail(const std::string &what) const { fail_at(line_, what); }
    [[noreturn]] void fail_at(std::size_t line, const std::string &what) const;

private:
    template <typename T>
    T finite(const std::string &what);
    bool read_line();   // the next line with a record: false at the file's end
    void split();
    // KEY=A,B,... of `text`, the record at `line` named `record`.
    std::vector<double> values(const std::string &text, std::size_t line, const std::string &record,
                               const std::string &key, std::size_t count, double min, double max) const;

    std::string path_, what_, kind_;
    std::ifstream in_;
    std::string text_, record_;
    std::vector<std::pair<std::size_t, std::size_t>> fields_;   // after the record: [begin, end) in text_
    std::size_t field_ = 0, line_ = 0, algorithm_line_ = 0, settings_line_ = 0, scene_line_ = 0;
    DatabaseProvenance provenance_;
};

}  // namespace occu
