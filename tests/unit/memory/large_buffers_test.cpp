// SPDX-License-Identifier: MIT
// The large buffers' storage (memory/large_buffers.h): cache-line aligned below
// 2 MiB; from 2 MiB up 2 MiB aligned, on pages of its own (the mapping ends
// with the buffer's last page) advised for huge pages; and a vector on it
// keeps its values as it grows past 2 MiB and shrinks below.
#include "memory/large_buffers.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

namespace occu {
namespace {

bool aligned(const void *p, std::size_t alignment) { return reinterpret_cast<std::uintptr_t>(p) % alignment == 0; }

// The VmFlags of the mapping holding `p` (/proc/self/smaps), or "" where
// there is none to read.
std::string mapping_flags(const void *p)
{
    std::ifstream smaps("/proc/self/smaps");
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        std::uintptr_t from = 0, to = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> from >> dash >> to && dash == '-' && line.find(' ') != std::string::npos &&
            line.find(':') > line.find(' ')) {
            inside = from <= at && at < to;
            continue;
        }
        if (inside && line.rfind("VmFlags:", 0) == 0)
            return line;
    }
    return "";
}

TEST(LargeBuffers, BelowAHugePageCacheLineAligned)
{
    for (std::size_t bytes : {std::size_t(1), std::size_t(100), std::size_t(4096), huge_page_bytes - 1}) {
        void *p = allocate_large_buffer(bytes);
        EXPECT_TRUE(aligned(p, cache_line_bytes)) << bytes;
        static_cast<unsigned char *>(p)[bytes - 1] = 1;
        release_large_buffer(p, bytes);
    }
}

TEST(LargeBuffers, FromAHugePageOnHugePagesOfItsOwn)
{
    for (std::size_t bytes : {huge_page_bytes, huge_page_bytes + 1, 5 * huge_page_bytes + 12345}) {
        auto *p = static_cast<unsigned char *>(allocate_large_buffer(bytes));
        EXPECT_TRUE(aligned(p, huge_page_bytes)) << bytes;
        // Writable from end to end, and fresh: zeros until written.
        EXPECT_EQ(p[0], 0);
        EXPECT_EQ(p[bytes - 1], 0);
        p[0] = p[bytes - 1] = 7;
        // Advised for huge pages where the system knows the advice.
        const std::string flags = mapping_flags(p);
#ifdef __linux__
        ASSERT_FALSE(flags.empty());
        std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
        std::string modes;
        if (std::getline(thp, modes) && modes.find("[never]") == std::string::npos)
            EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
        // The last byte lies in the same mapping: whole pages of its own.
        EXPECT_EQ(mapping_flags(p + bytes - 1), flags);
#endif
        release_large_buffer(p, bytes);
    }
}

TEST(LargeBuffers, VectorKeepsItsValuesAcrossTheHugePageSize)
{
    LargeBuffer<float> values;
    const std::size_t count = 3 * huge_page_bytes / sizeof(float);
    for (std::size_t i = 0; i < count; ++i)
        values.push_back(float(i) * 0.5f);
    EXPECT_TRUE(aligned(values.data(), huge_page_bytes));
    for (std::size_t i = 0; i < count; ++i)
        ASSERT_EQ(values[i], float(i) * 0.5f) << i;
    values.resize(10);
    values.shrink_to_fit();
    EXPECT_TRUE(aligned(values.data(), cache_line_bytes));
    for (std::size_t i = 0; i < 10; ++i)
        EXPECT_EQ(values[i], float(i) * 0.5f);
}

}  // namespace
}  // namespace occu
