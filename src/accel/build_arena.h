// accel: the median-split build's temporaries: one block of memory per build, carved in order by
// take(), from huge pages, a populated mapping or the heap as its size asks (build_arena.cpp).
#pragma once

#include <cassert>
#include <cstddef>
#include <memory>

#include "simd/namespace.h"

namespace raylane::RAYLANE_ISA_NS::median_detail {

/// One block for all of a build's temporaries, carved in order by take(). Fresh pages are most
/// of what a first build pays for beyond a repeated one (bench_build's BM_BuildMedianFirst
/// against BM_BuildMedian: docs/performance.md, "Building"), so a block of large_block_bytes
/// (2 MiB) or more is huge pages (map_pages: one fault per 2 MiB, and few TLB misses in the radix
/// sort's scatter), one of populated_from (1 MiB) up to that an anonymous mapping whose 4 KiB pages
/// the kernel faults in with one call (MAP_POPULATE), a smaller one the heap's. Given back when the
/// build ends (unmap_pages keeps the newest huge-page blocks for the next build).
class TempBlock {
  public:
    explicit TempBlock(size_t bytes);
    ~TempBlock();
    TempBlock(const TempBlock&) = delete;
    TempBlock& operator=(const TempBlock&) = delete;

    /// The next n elements of type T, aligned to `alignment` bytes (the caller sized the block
    /// for them).
    template <class T>
    T* take(size_t n) {
        T* p = reinterpret_cast<T*>(base_ + used_);
        used_ += bytes_for<T>(n);
        assert(used_ <= size_);
        return p;
    }
    /// Bytes take() uses for n elements of T.
    template <class T>
    static size_t bytes_for(size_t n) {
        return (n * sizeof(T) + alignment - 1) & ~(alignment - 1);
    }

    /// Every take() starts a cache line (64 bytes).
    static constexpr size_t alignment = 64;
    /// Blocks from this size (1 MiB) up to large_block_bytes are mapped with MAP_POPULATE.
    static constexpr size_t populated_from = size_t(1) << 20;

  private:
    std::byte* base_ = nullptr;
    size_t size_ = 0, used_ = 0;
};

/// Starts the lifetime of n objects of the trivial type T at p (no code) and returns them.
template <class T>
T* begin_array(std::byte* p, size_t n) {
    T* a = reinterpret_cast<T*>(p);
    std::uninitialized_default_construct_n(a, n);
    return a;
}

}  // namespace raylane::RAYLANE_ISA_NS::median_detail
