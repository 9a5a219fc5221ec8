// core: large blocks of memory straight from the kernel (pages.h).
#include "core/pages.h"

#include <malloc.h>
#include <sys/mman.h>

#include <cstdint>
#include <limits>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

namespace raylane {

namespace {

constexpr size_t huge_page = size_t(2) << 20;
constexpr size_t kept_limit = size_t(256) << 20;  ///< bytes of given-back blocks kept at most

size_t round_up(size_t bytes, size_t to) { return (bytes + to - 1) & ~(to - 1); }

/// Blocks given back, the newest last, kept for a later map_pages of the same size: a film of
/// the next frame, the next build's arrays.
struct KeptBlocks {
    std::mutex mutex;
    std::vector<std::pair<std::byte*, size_t>> blocks;
    size_t bytes = 0;
};

KeptBlocks& kept() {
    static KeptBlocks* k = new KeptBlocks;  // never destroyed: blocks may be given back at exit
    return *k;
}

}  // namespace

std::byte* map_pages(size_t bytes) {
    if (bytes == 0 || bytes > std::numeric_limits<size_t>::max() / 2) throw std::bad_alloc();
    const size_t used = round_up(bytes, huge_page);
    {
        KeptBlocks& k = kept();
        const std::lock_guard lock(k.mutex);
        for (size_t i = k.blocks.size(); i-- > 0;) {
            if (k.blocks[i].second != used) continue;
            std::byte* block = k.blocks[i].first;
            k.blocks.erase(k.blocks.begin() + std::ptrdiff_t(i));
            k.bytes -= used;
            return block;
        }
    }
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
    const size_t used = round_up(bytes, huge_page);
    KeptBlocks& k = kept();
    const std::lock_guard lock(k.mutex);
    if (used > kept_limit) {
        munmap(block, used);
        return;
    }
    try {
        k.blocks.emplace_back(block, used);
    } catch (...) {  // no memory to remember it: give it back now
        munmap(block, used);
        return;
    }
    k.bytes += used;
    while (k.bytes > kept_limit) {  // the oldest go back to the kernel first
        munmap(k.blocks.front().first, k.blocks.front().second);
        k.bytes -= k.blocks.front().second;
        k.blocks.erase(k.blocks.begin());
    }
}

void keep_freed_memory() {
    mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest (HEAP_MAX_SIZE / 2)
    mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
}

}  // namespace raylane
