// SPDX-License-Identifier: MIT
#include "evaluation/session_command_line.h"

#include <stdexcept>

#include "cli/arguments.h"
#include "culling/registry.h"

namespace occu {

bool SessionCommandLine::take(const std::string &name, const std::string &value)
{
    const std::string &a = name, &v = value;
    if (a == "--strategies") {
        strategies = list_items(v, ',');
        if (strategies.empty())
            throw std::invalid_argument("--strategies is empty");
    } else if (a == "--size") {
        const std::size_t x = v.find('x');
        const std::string wants = a + " wants PIXELS or WIDTHxHEIGHT, each side an integer in 16.." +
                                  std::to_string(max_size) + ", got '" + v + "'";
        try {
            if (x == std::string::npos) {
                square(int(integer_option(a, v, 16, max_size)));
            } else {
                // Digits only on either side: strtol would take " 64" or "+64".
                const std::string w = v.substr(0, x), h = v.substr(x + 1);
                auto digits = [](const std::string &t) {
                    return !t.empty() && t.find_first_not_of("0123456789") == std::string::npos;
                };
                if (!digits(w) || !digits(h))
                    throw std::invalid_argument(wants);
                const int wide = int(integer_option(a, w, 16, max_size)), high = int(integer_option(a, h, 16, max_size));
                width = wide;
                height = high;
            }
        } catch (const std::invalid_argument &) {
            throw std::invalid_argument(wants);
        }
    } else if (a == "--driver") {
        try {
            driver = gl::parse_driver(v);
        } catch (const std::invalid_argument &e) {
            throw std::invalid_argument(a + ": " + e.what());
        }
    } else if (a == "--allocator") {
        allocator = parse_allocator_policy(a, v);
    } else if (a == "--look") {
        if (v == "flat")
            look = Look::flat;
        else if (v == "scene")
            look = Look::scene;
        else
            throw std::invalid_argument(a + " wants flat or scene, got '" + v + "'");
    } else if (a == "--databases") {
        databases = v;
    } else if (a == "--make-databases") {
        make_databases = make_databases_option(a, v);
    } else if (!traversal_options) {
        return false;
    } else if (a == "--set") {
        common.push_back(v);
    } else if (a == "--batch") {
        batch = int(integer_option(a, v, 1, 4096));
    } else if (a == "--coherence") {
        coherence = switch_option(a, v);
    } else if (a == "--switch-off") {
        switch_off = number_option(a, v, 0.0, 1.0);
    } else {
        return false;
    }
    return true;
}

Look SessionCommandLine::look_for(const std::string &scene_name) const
{
    if (look)
        return *look;
    return scene_name.empty() || scene_name == "city" || scene_name == "field" ? Look::flat : Look::scene;
}

std::string SessionCommandLine::size_name() const
{
    return width == height ? std::to_string(width) : std::to_string(width) + "x" + std::to_string(height);
}

void SessionCommandLine::check_strategies(const std::vector<std::string> &specs) const
{
    std::vector<StrategyChoice> chosen;
    for (const std::string &s : specs)
        chosen.push_back(choose_strategy(s, common));
    check_common_settings(chosen, common);
}

SessionOptions SessionCommandLine::session_options(DatabaseProvider &provider) const
{
    SessionOptions so;
    so.allocator = allocator;
    so.batch = std::size_t(batch);
    so.coherence = coherence;
    so.switch_off = switch_off;
    so.databases = &provider;
    so.look = look.value_or(Look::flat);
    return so;
}

}  // namespace occu
