// core: large blocks of memory straight from the kernel, for the few arrays of tens of megabytes
// a render writes once (the film, its 8-bit bytes).
#pragma once

#include <cstddef>

namespace raylane {

/// Blocks of at least this many bytes come from map_pages.
inline constexpr size_t large_block_bytes = size_t(4) << 20;

/// A zero-filled block of `bytes`, aligned to 2 MiB and advised as transparent huge pages, so
/// that its first touch costs one page fault per 2 MiB instead of one per 4 KiB: on this VM a
/// 25 MB film written by two threads takes 26–29 ms of page faults that way against 42–60 ms
/// (docs/performance.md, "The whole command"). Where the kernel gives no huge pages it is an
/// ordinary mapping. Throws std::bad_alloc.
std::byte* map_pages(size_t bytes);

/// Returns a block of map_pages(bytes) to the kernel.
void unmap_pages(std::byte* block, size_t bytes) noexcept;

}  // namespace raylane
