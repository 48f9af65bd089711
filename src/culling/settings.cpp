// SPDX-License-Identifier: MIT
#include "culling/settings.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "cli/arguments.h"

namespace occu {

namespace {

std::string format_number(double v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

std::string SettingSpec::describe() const
{
    std::string d = name + "=" + (default_value.empty() ? "FILE" : default_value) + " (";
    switch (kind) {
    case Kind::integer: d += std::to_string(long(min)) + ".." + std::to_string(long(max)); break;
    case Kind::number: d += format_number(min) + ".." + format_number(max); break;
    case Kind::choice:
        for (std::size_t i = 0; i < choices.size(); ++i)
            d += (i ? "|" : "") + choices[i];
        break;
    case Kind::on_off: d += "on|off"; break;
    case Kind::path: d += "a file"; break;
    }
    if (role == Role::approximation)
        d += "; approximation, exact at 0";
    else if (role == Role::cost && !off.empty())
        d += "; " + off + " turns it off";
    return d + "): " + help;
}

Settings::Settings(std::string owner, const std::vector<SettingSpec> *specs) : owner_(std::move(owner)), specs_(specs)
{
    for (const SettingSpec &s : *specs_)
        values_[s.name] = s.default_value;
}

bool Settings::knows(const std::string &key) const
{
    return values_.count(key) != 0;
}

const SettingSpec &Settings::spec(const std::string &key) const
{
    for (const SettingSpec &s : *specs_)
        if (s.name == key)
            return s;
    std::string known;
    for (const SettingSpec &s : *specs_)
        known += (known.empty() ? "" : ", ") + s.name;
    throw std::invalid_argument(owner_ + " has no setting '" + key + "' (" +
                                (known.empty() ? std::string("it has none") : "known: " + known) + ")");
}

void Settings::set(const std::string &key, const std::string &value)
{
    const SettingSpec &s = spec(key);
    const std::string option = owner_ + " " + key;
    switch (s.kind) {
    case SettingSpec::Kind::integer: integer_option(option, value, long(s.min), long(s.max)); break;
    case SettingSpec::Kind::number: number_option(option, value, s.min, s.max); break;
    case SettingSpec::Kind::on_off: switch_option(option, value); break;
    case SettingSpec::Kind::choice: {
        bool found = false;
        std::string list;
        for (const std::string &c : s.choices) {
            found = found || c == value;
            list += (list.empty() ? "" : ", ") + c;
        }
        if (!found)
            throw std::invalid_argument(option + " wants one of " + list + ", got '" + value + "'");
        break;
    }
    case SettingSpec::Kind::path:
        if (value.empty())
            throw std::invalid_argument(option + " wants a file name");
        break;
    }
    values_[key] = value;
}

void Settings::set_all(const std::string &assignments)
{
    std::stringstream in(assignments);
    for (std::string item; std::getline(in, item, ':');) {
        if (item.empty())
            continue;
        const auto eq = item.find('=');
        if (eq == std::string::npos || eq == 0)
            throw std::invalid_argument(owner_ + ": setting '" + item + "' is not key=value");
        set(item.substr(0, eq), item.substr(eq + 1));
    }
}

long Settings::integer(const std::string &key) const
{
    (void)spec(key);
    return std::strtol(values_.at(key).c_str(), nullptr, 10);
}

double Settings::number(const std::string &key) const
{
    (void)spec(key);
    return std::strtod(values_.at(key).c_str(), nullptr);
}

bool Settings::on(const std::string &key) const
{
    (void)spec(key);
    return values_.at(key) == "on";
}

const std::string &Settings::text(const std::string &key) const
{
    (void)spec(key);
    return values_.at(key);
}

bool Settings::exact() const
{
    for (const SettingSpec &s : *specs_)
        if (s.role == SettingSpec::Role::approximation && std::strtod(values_.at(s.name).c_str(), nullptr) != 0.0)
            return false;
    return true;
}

std::string Settings::changed() const
{
    std::string out;
    for (const SettingSpec &s : *specs_)
        if (values_.at(s.name) != s.default_value)
            out += (out.empty() ? "" : ":") + s.name + "=" + values_.at(s.name);
    return out;
}

SettingSpec integer_setting(std::string name, long default_value, long min, long max, SettingSpec::Role role,
                            std::string help, std::string off)
{
    SettingSpec s;
    s.name = std::move(name);
    s.kind = SettingSpec::Kind::integer;
    s.role = role;
    s.default_value = std::to_string(default_value);
    s.min = double(min);
    s.max = double(max);
    s.help = std::move(help);
    s.off = std::move(off);
    return s;
}

SettingSpec number_setting(std::string name, double default_value, double min, double max, SettingSpec::Role role,
                           std::string help, std::string off)
{
    SettingSpec s;
    s.name = std::move(name);
    s.kind = SettingSpec::Kind::number;
    s.role = role;
    s.default_value = format_number(default_value);
    s.min = min;
    s.max = max;
    s.help = std::move(help);
    s.off = std::move(off);
    return s;
}

SettingSpec choice_setting(std::string name, std::vector<std::string> choices, std::string help,
                           SettingSpec::Role role)
{
    SettingSpec s;
    s.name = std::move(name);
    s.kind = SettingSpec::Kind::choice;
    s.role = role;
    s.default_value = choices.front();
    s.choices = std::move(choices);
    s.help = std::move(help);
    return s;
}

SettingSpec on_off_setting(std::string name, bool default_value, SettingSpec::Role role, std::string help)
{
    SettingSpec s;
    s.name = std::move(name);
    s.kind = SettingSpec::Kind::on_off;
    s.role = role;
    s.default_value = default_value ? "on" : "off";
    s.help = std::move(help);
    return s;
}

SettingSpec path_setting(std::string name, std::string help)
{
    SettingSpec s;
    s.name = std::move(name);
    s.kind = SettingSpec::Kind::path;
    s.role = SettingSpec::Role::choice;
    s.help = std::move(help);
    return s;
}

}  // namespace occu
