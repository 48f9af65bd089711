// SPDX-License-Identifier: MIT
// Numbers in occu's text files (route files, occluder databases). The
// library keeps world coordinates as floats, so a coordinate field must be
// a number whose float is finite: strtod reads "nan", "inf" and numbers
// beyond float range, none of which a file may bring in unnoticed.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace occu {

// Reads all of `text` as a float into `value`. Returns why it is not a
// finite float ("not a number", "not a finite number", ...), to follow the
// field's name and text in a message; empty when it is one.
inline std::string read_finite_float(const std::string &text, float &value)
{
    char *end = nullptr;
    errno = 0;
    const double x = std::strtod(text.c_str(), &end);
    if (text.empty() || *end)
        return "not a number";
    if (!std::isfinite(x))
        return "not a finite number";
    if (std::fabs(x) > double(std::numeric_limits<float>::max()))
        return "not a finite number in float range (magnitude at most 3.4e38)";
    value = float(x);
    return {};
}

}  // namespace occu
