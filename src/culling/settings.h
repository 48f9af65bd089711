// SPDX-License-Identifier: MIT
// A strategy's settings: declared by its family (name, kind, default,
// range), parsed from "key=value" text, validated, and read by name.
//
// Every knob is one of three roles, and the role fixes how it is named:
//   approximation  trades pixels for time; always called `tolerance`, in the
//                  family's own unit, exact (conservative) at 0;
//   cost           a heuristic that never changes a pixel (it only decides
//                  where testing is worth it); it names the quantity it
//                  bounds, and `off` says the value that turns it off;
//   choice         picks a variant (which occluders, which comparison).
// So every approximation reaches exact at tolerance=0, and every heuristic
// can be turned off, which is what benchmarks of time against error sweep.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace occu {

struct SettingSpec {
    enum class Kind { integer, number, choice, on_off, path };
    enum class Role { approximation, cost, choice };
    std::string name;
    Kind kind = Kind::number;
    Role role = Role::choice;
    std::string default_value;
    double min = 0.0, max = 0.0;          // integer and number: the closed range
    std::vector<std::string> choices;     // choice
    std::string off;                      // cost: the value that turns it off (empty: none)
    std::string help;

    // "tolerance=0 (0..1; approximation, exact at 0)": for --help.
    std::string describe() const;
};

class Settings {
public:
    // `owner` names the strategy in error messages.
    Settings(std::string owner, const std::vector<SettingSpec> *specs);

    // Throws std::invalid_argument naming the owner, the key and the known
    // keys (unknown key), or the key, its range and the value (bad value).
    void set(const std::string &key, const std::string &value);
    // "key=value[:key=value...]".
    void set_all(const std::string &assignments);
    bool knows(const std::string &key) const;

    long integer(const std::string &key) const;
    double number(const std::string &key) const;
    bool on(const std::string &key) const;
    const std::string &text(const std::string &key) const;

    // Every approximation knob at its exact value (tolerance=0).
    bool exact() const;
    // The settings that differ from their defaults, "key=value:...".
    std::string changed() const;

private:
    const SettingSpec &spec(const std::string &key) const;
    std::string owner_;
    const std::vector<SettingSpec> *specs_;
    std::map<std::string, std::string> values_;
};

// Convenience constructors for families' setting tables.
SettingSpec integer_setting(std::string name, long default_value, long min, long max, SettingSpec::Role role,
                            std::string help, std::string off = "");
SettingSpec number_setting(std::string name, double default_value, double min, double max, SettingSpec::Role role,
                           std::string help, std::string off = "");
// A choice whose role is cost (the cheaper first) trades time for culling,
// and occu-bench-knobs sweeps it; the others are not knobs.
SettingSpec choice_setting(std::string name, std::vector<std::string> choices, std::string help,
                           SettingSpec::Role role = SettingSpec::Role::choice);
SettingSpec on_off_setting(std::string name, bool default_value, SettingSpec::Role role, std::string help);
SettingSpec path_setting(std::string name, std::string help);

}  // namespace occu
