// core: large blocks of memory straight from the kernel, for the few arrays of megabytes that a
// render writes once (the film and its 8-bit bytes, a mesh's BVH and vertices in leaf order, the
// build's temporaries), and the heap setting of raylane and its benchmarks.
#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <new>
#include <utility>

namespace raylane {

#if defined(__SANITIZE_ADDRESS__)
#define RAYLANE_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RAYLANE_ADDRESS_SANITIZER 1
#endif
#endif

/// Blocks of at least this many bytes (one huge page) come from map_pages. Under
/// AddressSanitizer none do: its allocator puts red zones around every array and keeps freed
/// memory from being handed out again at once, which mapped and reused blocks would hide.
#if defined(RAYLANE_ADDRESS_SANITIZER)
inline constexpr size_t large_block_bytes = std::numeric_limits<size_t>::max();
#else
inline constexpr size_t large_block_bytes = size_t(2) << 20;
#endif

/// A block of `bytes` rounded up to whole huge pages (2 MiB), aligned to one and advised as
/// transparent huge pages, so that its first touch costs one page fault per 2 MiB instead of
/// one per 4 KiB (a film of megabytes is written once a frame, and its page faults would cost
/// as much as the writes). Where the kernel gives no huge pages it is an ordinary mapping. A block
/// of the same size given back earlier is taken first, its pages already in: its contents are
/// unspecified. Throws std::bad_alloc.
std::byte* map_pages(size_t bytes);

/// Gives back a block of map_pages(bytes). The newest 256 MiB of given-back blocks are kept for
/// map_pages (the next frame's film, the next build's arrays); the rest go back to the kernel.
void unmap_pages(std::byte* block, size_t bytes) noexcept;

/// Makes glibc's malloc keep what is freed: blocks up to 32 MiB come from the heap, which is
/// never trimmed. By default it maps blocks over a threshold that moves with what was freed last
/// and returns the heap's top to the kernel, so memory freed by one phase (the loader's, the
/// build's) is faulted in again by the next, at 6–15 us a page where measured: `raylane render
/// scenes/dragon.json` takes 0.12 s with it and 0.12–0.17 s without. Called first by raylane's
/// main and by every benchmark program, so that they measure the same heap.
void keep_freed_memory();

/// std::allocator for the large arrays that their makers overwrite: its value-initialising
/// construct() default-initialises instead, so a vector of floats grown by resize() is left
/// unwritten (a 1080p film is 25 MB that the renderers overwrite anyway), and blocks of
/// large_block_bytes or more come from map_pages (huge pages where the kernel has them).
/// Everything else is std::allocator's.
template <class T>
struct OverwriteAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = OverwriteAllocator<U>;
    };
    OverwriteAllocator() = default;
    template <class U>
    OverwriteAllocator(const OverwriteAllocator<U>&) noexcept {}
    T* allocate(size_t n) {
        if (n > std::numeric_limits<size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
        if (n * sizeof(T) >= large_block_bytes)
            return reinterpret_cast<T*>(map_pages(n * sizeof(T)));
        return std::allocator<T>::allocate(n);
    }
    void deallocate(T* p, size_t n) noexcept {
        if (n * sizeof(T) >= large_block_bytes)
            unmap_pages(reinterpret_cast<std::byte*>(p), n * sizeof(T));
        else
            std::allocator<T>::deallocate(p, n);
    }
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

}  // namespace raylane
