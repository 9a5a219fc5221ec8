// accel: the median-split build's temporaries (build_arena.h): where a TempBlock's memory comes
// from and goes back to.
#include "accel/build_arena.h"

#include <sys/mman.h>

#include <new>

#include "core/pages.h"

namespace raylane::RAYLANE_ISA_NS::median_detail {
namespace {

#if defined(RAYLANE_ADDRESS_SANITIZER)
constexpr bool sanitized = true;  // the sanitizer's allocator: red zones (pages.h)
#else
constexpr bool sanitized = false;
#endif

}  // namespace

TempBlock::TempBlock(size_t bytes) : size_(bytes) {
    if (bytes >= large_block_bytes) {
        base_ = map_pages(bytes);
    } else if (bytes >= populated_from && !sanitized) {
        void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE,
                       MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
        if (p == MAP_FAILED) throw std::bad_alloc();
        base_ = static_cast<std::byte*>(p);
    } else {
        base_ = static_cast<std::byte*>(::operator new(bytes, std::align_val_t(alignment)));
    }
}

TempBlock::~TempBlock() {
    if (size_ >= large_block_bytes)
        unmap_pages(base_, size_);
    else if (size_ >= populated_from && !sanitized)
        munmap(base_, size_);
    else
        ::operator delete(base_, std::align_val_t(alignment));
}

}  // namespace raylane::RAYLANE_ISA_NS::median_detail
