// core: map_pages and OverwriteAllocator (pages.h): huge-page-aligned blocks, a block given back
// taken again by the next request of its size with its pages in, small arrays from the heap.
#include "core/pages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <new>
#include <vector>

namespace raylane {
namespace {

constexpr size_t mib = size_t(1) << 20;

bool huge_page_aligned(const void* p) { return reinterpret_cast<uintptr_t>(p) % (2 * mib) == 0; }

TEST(MapPages, GivesAlignedBlocksAndTakesAGivenBackOneAgain) {
    std::byte* a = map_pages(3 * mib);
    ASSERT_TRUE(huge_page_aligned(a));
    std::memset(a, 0x5a, 4 * mib);  // rounded up to whole huge pages: 4 MiB are usable
    unmap_pages(a, 3 * mib);
    // the same rounded size: the same block, as it was left
    std::byte* b = map_pages(4 * mib - 1);
    EXPECT_EQ(b, a);
    EXPECT_EQ(b[0], std::byte{0x5a});
    EXPECT_EQ(b[4 * mib - 1], std::byte{0x5a});
    // another size: not b, though b is given back first
    unmap_pages(b, 4 * mib - 1);
    std::byte* c = map_pages(5 * mib);
    ASSERT_TRUE(huge_page_aligned(c));
    EXPECT_NE(c, b);
    std::memset(c, 1, 6 * mib);
    unmap_pages(c, 5 * mib);
    EXPECT_THROW(map_pages(0), std::bad_alloc);
    EXPECT_THROW(map_pages(std::numeric_limits<size_t>::max() - 1), std::bad_alloc);
}

TEST(OverwriteAllocator, PutsLargeArraysOnHugePagesAndSmallOnesOnTheHeap) {
#if defined(RAYLANE_ADDRESS_SANITIZER)
    GTEST_SKIP() << "under AddressSanitizer every array is the sanitizer's";
#else
    std::vector<float, OverwriteAllocator<float> > large(large_block_bytes / sizeof(float), 0.5f);
    EXPECT_TRUE(huge_page_aligned(large.data()));
    large.back() = 1.0f;
    std::vector<float, OverwriteAllocator<float> > small(1000, 2.0f);  // values still assigned
    EXPECT_EQ(small[999], 2.0f);
    small.resize(2000);
    EXPECT_EQ(small[0], 2.0f);
    // growing a large array moves its elements
    large.resize(large.size() * 2);
    EXPECT_EQ(large[0], 0.5f);
    EXPECT_EQ(large[large_block_bytes / sizeof(float) - 1], 1.0f);
#endif
}

}  // namespace
}  // namespace raylane
