// core: large blocks of memory straight from the kernel (pages.h).
#include "core/pages.h"

#include <malloc.h>
#include <sys/mman.h>

#include <cstdint>
#include <limits>
#include <new>

namespace raylane {

namespace {

constexpr size_t huge_page = size_t(2) << 20;

size_t round_up(size_t bytes, size_t to) { return (bytes + to - 1) & ~(to - 1); }

}  // namespace

std::byte* map_pages(size_t bytes) {
    const size_t used = round_up(bytes, huge_page);
    // map a huge page more than needed, then return the unaligned head and the tail
    const size_t mapped = used + huge_page;
    void* p = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    const uintptr_t start = reinterpret_cast<uintptr_t>(p);
    const uintptr_t aligned = round_up(start, huge_page);
    if (aligned > start) munmap(p, aligned - start);
    const uintptr_t end = start + mapped, block_end = aligned + used;
    if (end > block_end) munmap(reinterpret_cast<void*>(block_end), end - block_end);
    auto* block = reinterpret_cast<std::byte*>(aligned);
    madvise(block, used, MADV_HUGEPAGE);  // advice only: without huge pages, 4 KiB ones
    return block;
}

void unmap_pages(std::byte* block, size_t bytes) noexcept {
    munmap(block, round_up(bytes, huge_page));
}

void keep_freed_memory() {
    mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest (HEAP_MAX_SIZE / 2)
    mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
}

}  // namespace raylane
