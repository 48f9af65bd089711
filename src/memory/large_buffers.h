// SPDX-License-Identifier: MIT
// Storage for the buffers a frame reads all over: the depth buffer and
// its partial layer (raster/depth_rasterizer.h), the triangle choice's
// blocks (occluders/choice_kernels.h).
// Every buffer is cache-line aligned: their rows of eight floats (32
// bytes) are loaded and stored whole, and with malloc's 16-byte alignment
// every other one would straddle two cache lines. From 2 MiB up a buffer
// also lies on pages of its own, 2 MiB aligned and asked for 2 MiB pages
// (Linux's transparent huge pages) before their first touch: a frame that
// jumps across megabytes of one (the city's 270 000 triangles' choice
// blocks: 14 MB) costs with 4 KiB pages a TLB miss, a page walk, nearly
// every jump. Those pages come from a mapping of their own, never from the
// heap: memory the heap gives back has mostly been touched before (the
// benchmarks keep freed memory in the process, evaluation/allocator.h),
// and a page touched before the advice stays a 4 KiB one. Below 2 MiB the
// TLB reaches over the buffer anyway, and a huge page would hold mostly
// nothing.
#pragma once

#include <cstddef>
#include <vector>

namespace occu {

// From this size up, a buffer lies on 2 MiB pages of its own.
constexpr std::size_t huge_page_bytes = std::size_t(2) << 20;
constexpr std::size_t cache_line_bytes = 64;

// `bytes` of storage as the header says (never null: throws
// std::bad_alloc), and its release (the same `bytes`).
void *allocate_large_buffer(std::size_t bytes);
void release_large_buffer(void *storage, std::size_t bytes);

template <class T>
struct LargeBufferAllocator {
    using value_type = T;
    LargeBufferAllocator() = default;
    template <class U>
    LargeBufferAllocator(const LargeBufferAllocator<U> &) {}
    T *allocate(std::size_t n) { return static_cast<T *>(allocate_large_buffer(n * sizeof(T))); }
    void deallocate(T *p, std::size_t n) { release_large_buffer(p, n * sizeof(T)); }
    template <class U>
    bool operator==(const LargeBufferAllocator<U> &) const { return true; }
    template <class U>
    bool operator!=(const LargeBufferAllocator<U> &) const { return false; }
};
template <class T>
using LargeBuffer = std::vector<T, LargeBufferAllocator<T>>;

}  // namespace occu
