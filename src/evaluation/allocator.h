// SPDX-License-Identifier: MIT
// What the C library's allocator does with freed memory while a program
// measures. glibc's malloc gives large freed blocks back to the kernel
// (munmap of blocks over M_MMAP_THRESHOLD, trimming the heap's top over
// M_TRIM_THRESHOLD), so a renderer that frees and allocates its per-frame
// memory faults it in again every frame, and how many faults a frame takes
// depends on which other strategies share the process: llvmpipe's scene
// memory beside `chc` cost a third of the process under page faults
// (docs/occlusion-unit-llvmpipe.md). Every benchmark therefore runs with
// freed memory kept in the process unless told otherwise, and counts the
// page faults per frame either way.
#pragma once

#include <string>

namespace occu {

enum class AllocatorPolicy {
    keep_freed,   // freed memory stays mapped in the process (the benchmarks' default)
    system,       // the C library's defaults
};

// "keep" or "system"; throws std::invalid_argument naming `option`.
AllocatorPolicy parse_allocator_policy(const std::string &option, const std::string &text);
const char *allocator_policy_name(AllocatorPolicy policy);

// Applies `policy` to the whole process (glibc's mallopt); call before the
// measured work. Throws std::runtime_error if the C library refuses it.
void control_allocator(AllocatorPolicy policy);

}  // namespace occu
