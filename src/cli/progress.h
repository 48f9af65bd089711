// SPDX-License-Identifier: MIT
// A progress bar on stderr, only when stderr is a terminal (logs and CI
// output stay clean).
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>

#include <unistd.h>

namespace occu {

inline void progress(const std::string &what, long done, long total)
{
    if (!isatty(STDERR_FILENO))
        return;
    const long width = 30, filled = done * width / std::max(total, 1L);
    std::fprintf(stderr, "\r%-12s [%s%s] %ld/%ld", what.c_str(), std::string(std::size_t(filled), '#').c_str(),
                 std::string(std::size_t(width - filled), ' ').c_str(), done, total);
    if (done == total)
        std::fprintf(stderr, "\n");
}

}  // namespace occu
