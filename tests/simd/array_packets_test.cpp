// tests for simd/array_packets.h: the masked load and the byte gather at every supported width,
// against memory that faults where an inactive lane would read.
#include "simd/array_packets.h"

#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <new>
#include <random>
#include <vector>

#include "support/lane_helpers.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

// ---- helpers ---------------------------------------------------------------------------------

template <class T>
class ArrayPacketsTest : public ::testing::Test {};
TYPED_TEST_SUITE(ArrayPacketsTest, Widths, WidthName);

/// Random lane bits below bit W; every 8th draw is all-off and every 8th (offset) all-on.
template <int W>
uint32_t active_bits_for_round(std::mt19937& rng, int round) {
    constexpr uint32_t every_lane = (1u << W) - 1u;
    if (round % 8 == 0) return 0u;
    if (round % 8 == 4) return every_lane;
    return static_cast<uint32_t>(rng()) & every_lane;
}

/// Random bit patterns as floats (NaN payloads, denormals and -0.0 among them).
template <int W>
std::array<float, W> bit_pattern_lanes(std::mt19937& rng) {
    std::array<float, W> a;
    for (float& v : a) v = std::bit_cast<float>(static_cast<uint32_t>(rng()));
    return a;
}

// ---- masked load ------------------------------------------------------------------------------

/// A page of memory followed by one that cannot be read: a read at or past end() faults.
class GuardedPage {
  public:
    GuardedPage() : size_(static_cast<size_t>(sysconf(_SC_PAGESIZE))) {
        void* p =
            mmap(nullptr, 2 * size_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p == MAP_FAILED) throw std::bad_alloc();
        base_ = static_cast<std::byte*>(p);
        if (mprotect(base_ + size_, size_, PROT_NONE) != 0) throw std::bad_alloc();
    }
    ~GuardedPage() { munmap(base_, 2 * size_); }
    GuardedPage(const GuardedPage&) = delete;
    GuardedPage& operator=(const GuardedPage&) = delete;
    std::byte* end() const { return base_ + size_; }

  private:
    size_t size_;
    std::byte* base_ = nullptr;
};

TYPED_TEST(ArrayPacketsTest, MaskedLoadReadsOnlyActiveLanes) {
    constexpr int W = TypeParam::value;
    const GuardedPage page;
    std::mt19937 rng(29);
    for (int r = 0; r < rounds; ++r) {
        // the first n lanes end the readable page; the lanes from n on would fault
        const int n = static_cast<int>(rng() % (W + 1));
        const auto a = bit_pattern_lanes<W>(rng);
        float* p = reinterpret_cast<float*>(page.end()) - n;
        std::memcpy(p, a.data(), sizeof(float) * static_cast<size_t>(n));
        const uint32_t b = active_bits_for_round<W>(rng, r) & ((1u << n) - 1u);
        std::array<float, W> got;
        std::array<int32_t, W> got_int;
        store(got.data(), load(p, mask_from_bits<W>(b)));
        store(got_int.data(), load(reinterpret_cast<const int32_t*>(p), mask_from_bits<W>(b)));
        for (int l = 0; l < W; ++l) {
            const uint32_t want = (b >> l) & 1u ? bits_of(a[l]) : 0u;
            ASSERT_EQ(bits_of(got[l]), want) << "lane " << l;
            ASSERT_EQ(static_cast<uint32_t>(got_int[l]), want) << "lane " << l;
        }
    }
}

// ---- byte gather ------------------------------------------------------------------------------

TYPED_TEST(ArrayPacketsTest, ByteGatherZeroExtendsTheActiveLanesBytes) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(30);
    constexpr int size = 53;
    std::vector<uint8_t> table(size + gather_u8_padding);  // the padding after the last byte
    for (uint8_t& v : table) v = static_cast<uint8_t>(rng());
    for (int r = 0; r < rounds; ++r) {
        const uint32_t b = active_bits_for_round<W>(rng, r);
        std::array<int32_t, W> idx;
        for (int l = 0; l < W; ++l) {
            // an inactive lane's index points far outside the table: reading it would fault
            idx[l] = (b >> l) & 1u ? static_cast<int32_t>(rng() % size) : (1 << 30) + l;
        }
        const auto got =
            lanes_of<W>(gather_u8(table.data(), load<W>(idx.data()), mask_from_bits<W>(b)));
        for (int l = 0; l < W; ++l) {
            const int32_t want = (b >> l) & 1u ? table[static_cast<size_t>(idx[l])] : 0;
            ASSERT_EQ(got[l], want) << "lane " << l;
        }
    }
}

}  // namespace
}  // namespace raylane
