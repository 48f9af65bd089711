// SPDX-License-Identifier: MIT
#include "culling/database_file.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "library_code_hash.h"
#include "spatial/hierarchy.h"

#ifndef OCCU_MESA_BUILD
#define OCCU_MESA_BUILD "unknown"
#endif

namespace occu {

namespace {

bool is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Whether `text` reads back as written from a record's fields: on one
// line, no comment mark, no white space around it, and (for a `word`) none inside.
bool reads_back(const std::string &text, bool word)
{
    for (char c : text)
        if (c == '\n' || c == '#' || c == '\0' || (word && is_space(c)))
            return false;
    return text.empty() || (!is_space(text.front()) && !is_space(text.back()));
}

}  // namespace

const char *library_code_hash()
{
    return OCCU_LIBRARY_CODE_HASH;
}

const char *mesa_build()
{
    return OCCU_MESA_BUILD;
}

DatabaseProvenance DatabaseProvenance::current(std::string algorithm, std::string settings, std::string scene,
                                               bool made_with_mesa)
{
    return {std::move(algorithm), std::move(settings), std::move(scene), library_code_hash(),
            made_with_mesa ? mesa_build() : "none"};
}

std::string DatabaseProvenance::mismatch(const std::string &here) const
{
    if (scene != here)
        return "made for another scene (" + scene + "; this one is " + here + ")";
    if (mesa != "none" && mesa != mesa_build())
        return "made with another Mesa (" + mesa + "; this program runs on " + mesa_build() + ")";
    return {};
}

std::string DatabaseProvenance::difference(const DatabaseProvenance &o) const
{
    const std::pair<const char *, const std::string DatabaseProvenance::*> records[] = {
        {"algorithm", &DatabaseProvenance::algorithm}, {"settings", &DatabaseProvenance::settings},
        {"scene", &DatabaseProvenance::scene},         {"code", &DatabaseProvenance::code},
        {"mesa", &DatabaseProvenance::mesa}};
    for (const auto &[name, field] : records)
        if (this->*field != o.*field)
            return std::string(name) + " '" + this->*field + "' against '" + o.*field + "'";
    return {};
}

std::string DatabaseProvenance::key() const
{
    // 64-bit FNV-1a over the records, each ended by a line break (which no
    // record holds): a name, not a defence against collisions made on purpose.
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (const std::string *field : {&algorithm, &settings, &scene, &code, &mesa})
        for (unsigned char c : *field + '\n') {
            h ^= c;
            h *= 0x100000001b3ULL;
        }
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(h));
    return hex;
}

std::string scene_provenance(const Hierarchy &hierarchy)
{
    return hierarchy.fingerprint() + " leaves=" + std::to_string(hierarchy.leaf_count()) +
           " triangles=" + std::to_string(hierarchy.root().subtree_triangles);
}

std::string exact_number(double value)
{
    char text[32];
    const auto end = std::to_chars(text, text + sizeof(text), value).ptr;
    return std::string(text, end);
}

std::string exact_number(float value)
{
    char text[32];
    const auto end = std::to_chars(text, text + sizeof(text), value).ptr;
    return std::string(text, end);
}

DatabaseWriter::DatabaseWriter(const std::string &path, const std::string &kind, int version,
                               const DatabaseProvenance &p)
    : path_(path)
{
    // As the reader takes them: one word, or (settings, scene) the rest of
    // the line; only the settings may be empty.
    struct Record {
        const char *name;
        const std::string &text;
        bool word, may_be_empty;
    };
    const Record records[] = {{"algorithm", p.algorithm, true, false},
                              {"settings", p.settings, false, true},
                              {"scene", p.scene, false, false},
                              {"code", p.code, true, false},
                              {"mesa", p.mesa, true, false}};
    for (const Record &r : records)
        if (!reads_back(r.text, r.word) || (r.text.empty() && !r.may_be_empty))
            throw std::invalid_argument(path + ": the provenance's " + r.name + " '" + r.text +
                                        "' would not read back (empty, a line break, '#' or white space)");
    out_.open(path);
    if (!out_)
        throw std::runtime_error(path + ": cannot write");
    out_ << "occu-database " << kind << ' ' << version << '\n';
    for (const Record &r : records)
        out_ << r.name << (r.text.empty() ? "" : " ") << r.text << '\n';
}

void DatabaseWriter::finish()
{
    out_ << "end\n";
    if (!out_.flush())
        throw std::runtime_error(path_ + ": write failed");
    out_.close();
}

DatabaseReader::DatabaseReader(const std::string &path, const std::string &kind, int version, const std::string &what)
    : path_(path), what_(what), in_(path)
{
    if (!in_)
        throw std::runtime_error(path + ": cannot open " + what);
    if (!read_line())
        throw std::runtime_error(path + ": empty file, not an " + std::string("occu ") + what);
    const std::string header = "'occu-database " + kind + " " + std::to_string(version) + "'";
    if (record_ != "occu-database") {
        if (record_.rfind("occu-", 0) == 0)
            fail("'" + record_ + "' is the format before occu-database, whose provenance it lacks; make the " +
                 what + " again (occu-preprocess)");
        fail("not an occu " + what + " (expected " + header + ")");
    }
    kind_ = word("the kind");
    if (kind_ != kind && !kind.empty())
        fail("a database of " + kind_ + ", not an occu " + what + " (expected " + header + ")");
    if (const std::uint64_t v = count("the version", 1u << 30); v != std::uint64_t(version) && !kind.empty())
        fail(what + " version " + std::to_string(v) + ", this program reads version " + std::to_string(version));
    done();

    // The provenance, in this order; a record of one word names it (the
    // others take the rest of their line).
    struct Record {
        const char *name;
        std::string *field;
        const char *word;
        std::size_t *line;
    };
    std::size_t other_line = 0;
    const Record records[] = {{"algorithm", &provenance_.algorithm, "the algorithm", &algorithm_line_},
                              {"settings", &provenance_.settings, nullptr, &settings_line_},
                              {"scene", &provenance_.scene, nullptr, &scene_line_},
                              {"code", &provenance_.code, "the code hash", &other_line},
                              {"mesa", &provenance_.mesa, "the Mesa build", &other_line}};
    for (const Record &r : records) {
        if (!read_line())
            fail_at(line_ + 1, "ends before its " + std::string(r.name) + " record");
        if (record_ != r.name)
            fail("expected the " + std::string(r.name) + " record here (the provenance: algorithm, settings, scene, "
                 "code, mesa), got '" + record_ + "'");
        *r.line = line_;
        if (r.word) {
            *r.field = word(r.word);
            done();
        } else {
            *r.field = rest();
        }
    }
    if (provenance_.scene.empty())
        fail_at(scene_line_, "scene: what the " + what + " was made for missing");
}

void DatabaseReader::require_algorithm(const std::string &algorithm) const
{
    if (provenance_.algorithm != algorithm)
        fail_at(algorithm_line_, "algorithm '" + provenance_.algorithm + "': this reads the " + what_ + " of " +
                                     algorithm);
}

bool DatabaseReader::read_line()
{
    while (std::getline(in_, text_)) {
        ++line_;
        if (const auto hash = text_.find('#'); hash != std::string::npos)
            text_.erase(hash);
        split();
        if (!record_.empty())
            return true;
    }
    return false;
}

void DatabaseReader::split()
{
    // The first word is the record, the others its fields.
    fields_.clear();
    field_ = 0;
    record_.clear();
    for (std::size_t i = 0; i < text_.size();) {
        while (i < text_.size() && is_space(text_[i]))
            ++i;
        const std::size_t begin = i;
        while (i < text_.size() && !is_space(text_[i]))
            ++i;
        if (begin == i)
            break;
        if (record_.empty())
            record_ = text_.substr(begin, i - begin);
        else
            fields_.emplace_back(begin, i);
    }
}

bool DatabaseReader::next()
{
    if (!read_line())
        fail_at(line_ + 1, "ends before its end record (the file was cut short)");
    if (record_ != "end")
        return true;
    done();
    const std::size_t end_line = line_;
    if (read_line())
        fail("'" + record_ + "' after the end record (line " + std::to_string(end_line) + ")");
    line_ = end_line;
    return false;
}

std::string DatabaseReader::word(const std::string &what)
{
    if (!more())
        fail(record_ + ": " + what + " missing");
    const auto [begin, end] = fields_[field_++];
    return text_.substr(begin, end - begin);
}

std::string DatabaseReader::rest()
{
    if (!more())
        return {};
    const std::size_t begin = fields_[field_].first, end = fields_.back().second;
    field_ = fields_.size();
    return text_.substr(begin, end - begin);
}

double DatabaseReader::number(const std::string &what)
{
    return finite<double>(what);
}

float DatabaseReader::float_number(const std::string &what)
{
    return finite<float>(what);
}

template <typename T>
T DatabaseReader::finite(const std::string &what)
{
    const std::string text = word(what);
    T value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error == std::errc::invalid_argument || end != text.data() + text.size())
        fail(record_ + ": " + what + " is '" + text + "', not a number");
    if (error == std::errc::result_out_of_range || !std::isfinite(value))
        fail(record_ + ": " + what + " is '" + text + "', not a finite number" +
             (sizeof(T) == sizeof(float) ? " in float range" : ""));
    return value;
}

std::uint64_t DatabaseReader::count(const std::string &what, std::uint64_t max)
{
    const std::string text = word(what);
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size())
        fail(record_ + ": " + what + " is '" + text + "', not a whole number from 0 to " + std::to_string(max));
    if (value > max)
        fail(record_ + ": " + what + " is " + text + ", more than " + std::to_string(max));
    return value;
}

void DatabaseReader::done() const
{
    if (more())
        fail(record_ + ": more fields than it takes ('" + text_.substr(fields_[field_].first) + "')");
}

std::vector<double> DatabaseReader::setting(const std::string &key, std::size_t count, double min, double max) const
{
    return values(provenance_.settings, settings_line_, "settings", key, count, min, max);
}

double DatabaseReader::scene_number(const std::string &key, double min, double max) const
{
    return values(provenance_.scene, scene_line_, "scene", key, 1, min, max)[0];
}

std::vector<double> DatabaseReader::values(const std::string &s, std::size_t line, const std::string &record,
                                           const std::string &key, std::size_t count, double min, double max) const
{
    // Words KEY=VALUE; the last of one key counts.
    std::string text;
    bool found = false;
    for (std::size_t i = 0; i < s.size();) {
        while (i < s.size() && is_space(s[i]))
            ++i;
        std::size_t end = i;
        while (end < s.size() && !is_space(s[end]))
            ++end;
        if (end - i > key.size() && s.compare(i, key.size() + 1, key + "=") == 0) {
            text = s.substr(i + key.size() + 1, end - i - key.size() - 1);
            found = true;
        }
        i = end;
    }
    const std::string wants = count == 1 ? "a number" : std::to_string(count) + " numbers split by commas";
    if (!found)
        fail_at(line, record + ": " + key + "=VALUE missing (" + wants + ")");
    std::vector<double> values;
    for (std::size_t begin = 0; begin <= text.size();) {
        std::size_t end = text.find(',', begin);
        if (end == std::string::npos)
            end = text.size();
        double value = 0.0;
        const auto [stop, error] = std::from_chars(text.data() + begin, text.data() + end, value);
        if (error != std::errc() || stop != text.data() + end || !std::isfinite(value))
            fail_at(line, record + ": " + key + " is '" + text + "', not " + wants + " (finite)");
        if (!(value >= min && value <= max))
            fail_at(line, record + ": " + key + " is '" + text + "', its numbers from " + exact_number(min) +
                                        " to " + exact_number(max));
        values.push_back(value);
        begin = end + 1;
    }
    if (values.size() != count)
        fail_at(line, record + ": " + key + " is '" + text + "', not " + wants);
    return values;
}

void DatabaseReader::fail_at(std::size_t line, const std::string &what) const
{
    throw std::runtime_error(path_ + ":" + std::to_string(line) + ": " + what);
}

}  // namespace occu
