// SPDX-License-Identifier: MIT
// What the fuzz targets share: the fuzzer's bytes as a file the loaders
// read (they take paths, as the programs do), and the rule every target
// checks: bad input is refused with an exception that names it, never a
// crash, a hang, undefined behaviour or a sanitizer report.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace occu::fuzz {

// A file holding `data`, named with `suffix` (loaders choose formats by
// it), removed when the object goes.
class InputFile {
public:
    InputFile(const std::uint8_t *data, std::size_t size, const std::string &suffix)
    {
        const char *dir = std::getenv("TMPDIR");
        path_ = std::string(dir && *dir ? dir : "/tmp") + "/occu-fuzz-" + std::to_string(getpid()) + suffix;
        FILE *f = std::fopen(path_.c_str(), "wb");
        if (!f)
            std::abort();
        if (size && std::fwrite(data, 1, size, f) != size)
            std::abort();
        std::fclose(f);
    }
    ~InputFile() { std::remove(path_.c_str()); }
    const std::string &path() const { return path_; }

private:
    std::string path_;
};

// A refusal must say what it refused: the file's path in its message.
inline void require_named(const std::exception &e, const std::string &path)
{
    if (std::string(e.what()).find(path) == std::string::npos) {
        std::fprintf(stderr, "refusal does not name the input %s: %s\n", path.c_str(), e.what());
        std::abort();
    }
}

}  // namespace occu::fuzz
