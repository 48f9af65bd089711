// SPDX-License-Identifier: MIT
#include "evaluation/allocator.h"

#include <malloc.h>

#include <climits>
#include <stdexcept>

namespace occu {

AllocatorPolicy parse_allocator_policy(const std::string &option, const std::string &text)
{
    if (text == "keep")
        return AllocatorPolicy::keep_freed;
    if (text == "system")
        return AllocatorPolicy::system;
    throw std::invalid_argument(option + " wants 'keep' (freed memory stays in the process) or 'system' "
                                "(the C library's defaults), got '" + text + "'");
}

const char *allocator_policy_name(AllocatorPolicy policy)
{
    return policy == AllocatorPolicy::keep_freed ? "keep" : "system";
}

void control_allocator(AllocatorPolicy policy)
{
    if (policy == AllocatorPolicy::system)
        return;
    // Large blocks from the heap rather than their own mappings (the
    // largest threshold glibc accepts on 64-bit, 32 MiB: llvmpipe's scene
    // data blocks are far smaller), and the heap's top never trimmed.
    // Setting either also stops glibc's dynamic adjustment of the other.
    if (mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024) != 1 || mallopt(M_TRIM_THRESHOLD, INT_MAX) != 1)
        throw std::runtime_error("the C library refused to keep freed memory in the process (mallopt)");
}

}  // namespace occu
