// SPDX-License-Identifier: MIT
// Option values for occu's programs: each parser reads the whole text or
// throws std::invalid_argument with a message naming the option, the range
// and what was given, which the program prints as its usage error.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace occu {

// An integer in [lo, hi].
inline long integer_option(const std::string &option, const std::string &text, long lo, long hi)
{
    char *end = nullptr;
    const long x = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end || x < lo || x > hi)
        throw std::invalid_argument(option + " wants an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
                                    ", got '" + text + "'");
    return x;
}

// A number between lo and hi, each bound included unless open.
inline double number_option(const std::string &option, const std::string &text, double lo, double hi,
                            bool lo_open = false, bool hi_open = false)
{
    char *end = nullptr;
    const double x = std::strtod(text.c_str(), &end);
    const bool above = lo_open ? x > lo : x >= lo, below = hi_open ? x < hi : x <= hi;
    if (text.empty() || *end || !(above && below)) {
        char range[64];
        std::snprintf(range, sizeof(range), "%c%g, %g%c", lo_open ? '(' : '[', lo, hi, hi_open ? ')' : ']');
        throw std::invalid_argument(option + " wants a number in " + range + ", got '" + text + "'");
    }
    return x;
}

// The non-empty items of a list such as "a,b,,c" split at `by`.
inline std::vector<std::string> list_items(const std::string &list, char by)
{
    std::vector<std::string> items;
    std::stringstream in(list);
    for (std::string s; std::getline(in, s, by);)
        if (!s.empty())
            items.push_back(s);
    return items;
}

// Reads argv as "--name value" pairs, as every occu program takes its
// options: -h or --help, and a name without its value, go to `usage`
// (which exits); handle(name, value) returns false for a name it does not
// know, and a std::invalid_argument it throws goes to `usage` with its
// message.
template <class Usage, class Handle>
void for_each_option(int argc, char **argv, Usage &&usage, Handle &&handle)
{
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help")
            usage("");
        if (i + 1 >= argc)
            usage("unknown argument or missing value: '" + a + "'");
        const std::string v = argv[++i];
        try {
            if (!handle(a, v))
                usage("unknown argument '" + a + "'");
        } catch (const std::invalid_argument &e) {
            usage(e.what());
        }
    }
}

// "on" or "off".
inline bool switch_option(const std::string &option, const std::string &text)
{
    if (text != "on" && text != "off")
        throw std::invalid_argument(option + " wants on or off, got '" + text + "'");
    return text == "on";
}

}  // namespace occu
