// SPDX-License-Identifier: MIT
#include "memory/large_buffers.h"

#include <cstdint>
#include <new>

#include <sys/mman.h>

namespace occu {

namespace {

std::size_t whole_huge_pages(std::size_t bytes) { return (bytes + huge_page_bytes - 1) / huge_page_bytes * huge_page_bytes; }

}  // namespace

void *allocate_large_buffer(std::size_t bytes)
{
    if (bytes < huge_page_bytes)
        return ::operator new(bytes, std::align_val_t(cache_line_bytes));
    // A mapping one huge page longer than the buffer's whole pages, cut
    // down to them where they start on a 2 MiB boundary: what is left is
    // exactly the buffer's, so that release needs nothing but its size.
    const std::size_t length = whole_huge_pages(bytes);
    void *mapping = mmap(nullptr, length + huge_page_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapping == MAP_FAILED)
        throw std::bad_alloc();
    const auto start = reinterpret_cast<std::uintptr_t>(mapping);
    const std::uintptr_t aligned = (start + huge_page_bytes - 1) / huge_page_bytes * huge_page_bytes;
    if (aligned > start)
        munmap(mapping, aligned - start);
    munmap(reinterpret_cast<void *>(aligned + length), start + huge_page_bytes - aligned);
#ifdef MADV_HUGEPAGE
    // Advice only: where the system gives no huge pages, 4 KiB ones.
    madvise(reinterpret_cast<void *>(aligned), length, MADV_HUGEPAGE);
#endif
    return reinterpret_cast<void *>(aligned);
}

void release_large_buffer(void *storage, std::size_t bytes)
{
    if (bytes < huge_page_bytes)
        ::operator delete(storage, std::align_val_t(cache_line_bytes));
    else
        munmap(storage, whole_huge_pages(bytes));
}

}  // namespace occu
