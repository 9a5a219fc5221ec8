// tests for simd/lanes.h: lane access, mask queries, loops over active lanes, compaction, masked
// store and gather, at every supported width, for random masks including all-off and all-on.
#include "simd/lanes.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "support/lane_helpers.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

// ---- helpers ---------------------------------------------------------------------------------

template <class T>
class LanesTest : public ::testing::Test {};
TYPED_TEST_SUITE(LanesTest, Widths, WidthName);

template <int W>
constexpr uint32_t all_lanes = W == 32 ? ~0u : (1u << W) - 1u;

/// Random lane bits; every 8th draw is all-off and every 8th (offset) all-on.
template <int W>
uint32_t random_bits(std::mt19937& rng, int round) {
    if (round % 8 == 0) return 0u;
    if (round % 8 == 4) return all_lanes<W>;
    return static_cast<uint32_t>(rng()) & all_lanes<W>;
}

/// Values that must survive compaction bit for bit: NaN payloads, -0.0, denormals, lane tags.
template <int W>
std::array<float, W> tagged_lanes(std::mt19937& rng) {
    static constexpr uint32_t specials[] = {0x7fc01234u, 0xffa00001u, 0x80000000u, 0x00000001u,
                                            0x7f800000u};
    std::array<float, W> a;
    for (int l = 0; l < W; ++l) {
        const uint32_t pattern =
            rng() % 3 == 0 ? specials[rng() % 5] : static_cast<uint32_t>(rng());
        a[l] = std::bit_cast<float>(pattern);
    }
    return a;
}

// ---- lane access ----------------------------------------------------------------------------

TYPED_TEST(LanesTest, LaneIndexCountsFromZero) {
    constexpr int W = TypeParam::value;
    const auto lanes = lanes_of<W>(lane_index<W>());
    for (int l = 0; l < W; ++l) EXPECT_EQ(lanes[l], l);
}

TYPED_TEST(LanesTest, GetAndSetTouchOnlyTheirLane) {
    constexpr int W = TypeParam::value;
    for (int target = 0; target < W; ++target) {
        vfloat<W> v = to_float(lane_index<W>());
        vint<W> n = lane_index<W>();
        set(v, target, -1.5f);
        set(n, target, int32_t{-9});
        for (int l = 0; l < W; ++l) {
            EXPECT_EQ(get(v, l), l == target ? -1.5f : static_cast<float>(l));
            EXPECT_EQ(get(n, l), l == target ? -9 : l);
            EXPECT_EQ(get(v < vfloat<W>(0.0f), l), l == target);
        }
    }
}

TYPED_TEST(LanesTest, GatherReadsTheIndexedElements) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(2);
    float table[97];
    for (float& v : table) v = std::bit_cast<float>(static_cast<uint32_t>(rng()));
    for (int r = 0; r < rounds; ++r) {
        std::array<int32_t, W> idx;
        for (int32_t& i : idx) i = static_cast<int32_t>(rng() % 97);
        const auto got = lanes_of<W>(gather<W>(table, load<W>(idx.data())));
        for (int l = 0; l < W; ++l) ASSERT_EQ(bits_of(got[l]), bits_of(table[idx[l]]));
    }
}

TYPED_TEST(LanesTest, GatherRecords8ReadsWholeRecordsInLaneOrder) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(3);
    alignas(64) float table[41 * 8];
    for (float& v : table) v = std::bit_cast<float>(static_cast<uint32_t>(rng()));
    for (int r = 0; r < rounds; ++r) {
        std::array<int32_t, W> idx;
        for (int32_t& i : idx) i = static_cast<int32_t>(rng() % 41);
        if (r == 0) idx.fill(7);  // every lane the same record
        vfloat<W> out[8];
        gather_records8<W>(table, load<W>(idx.data()), out);
        for (int k = 0; k < 8; ++k) {
            const auto got = lanes_of<W>(out[k]);
            for (int l = 0; l < W; ++l)
                ASSERT_EQ(bits_of(got[l]), bits_of(table[8 * idx[l] + k]))
                    << "field " << k << ", lane " << l;
        }
    }
}

// ---- mask queries ---------------------------------------------------------------------------

TYPED_TEST(LanesTest, BitsRoundTripThroughMasks) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(20);
    for (int r = 0; r < rounds; ++r) {
        const uint32_t b = random_bits<W>(rng, r);
        const vmask<W> m = mask_from_bits<W>(b | ~all_lanes<W>);  // high bits are ignored
        ASSERT_EQ(bits(m), b);
        for (int l = 0; l < W; ++l) ASSERT_EQ(get(m, l), ((b >> l) & 1u) != 0);
    }
}

TYPED_TEST(LanesTest, BitsOfComparisonMasksMatchTheLanes) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(21);
    for (int r = 0; r < rounds; ++r) {
        std::array<float, W> a;
        for (float& v : a) v = std::uniform_real_distribution<float>(-1.0f, 1.0f)(rng);
        const vmask<W> m = load<W>(a.data()) < vfloat<W>(0.0f);
        uint32_t want = 0;
        for (int l = 0; l < W; ++l) want |= a[l] < 0.0f ? 1u << l : 0u;
        ASSERT_EQ(bits(m), want);
    }
}

TYPED_TEST(LanesTest, AnyAllNoneCountAndFirstActiveAgreeWithTheBits) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(22);
    for (int r = 0; r < rounds; ++r) {
        const uint32_t b = random_bits<W>(rng, r);
        const vmask<W> m = mask_from_bits<W>(b);
        int n = 0;
        int first = -1;
        for (int l = W - 1; l >= 0; --l) {
            if ((b >> l) & 1u) {
                ++n;
                first = l;
            }
        }
        ASSERT_EQ(any(m), n > 0);
        ASSERT_EQ(all(m), n == W);
        ASSERT_EQ(none(m), n == 0);
        ASSERT_EQ(count(m), n);
        ASSERT_EQ(first_active(m), first);
    }
    EXPECT_EQ(first_active(mask_from_bits<W>(0u)), -1);
    EXPECT_EQ(first_active(mask_from_bits<W>(1u << (W - 1))), W - 1);
}

TYPED_TEST(LanesTest, PrefixMaskHoldsTheFirstNLanes) {
    constexpr int W = TypeParam::value;
    for (int n = 0; n <= W; ++n) ASSERT_EQ(bits(prefix_mask<W>(n)), (1u << n) - 1u) << n;
}

TYPED_TEST(LanesTest, KeepFirstActiveKeepsTheLowestNActiveLanes) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(28);
    for (int r = 0; r < rounds; ++r) {
        const uint32_t b = random_bits<W>(rng, r);
        const uint32_t n = static_cast<uint32_t>(rng() % (W + 2));  // more than the lanes too
        uint32_t want = 0, kept = 0;
        for (int l = 0; l < W; ++l) {
            if (((b >> l) & 1u) && kept < n) {
                want |= 1u << l;
                ++kept;
            }
        }
        ASSERT_EQ(bits(keep_first_active(mask_from_bits<W>(b), n)), want)
            << "bits " << b << ", n " << n;
    }
}

TYPED_TEST(LanesTest, ForEachActiveVisitsActiveLanesInOrder) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(23);
    for (int r = 0; r < rounds; ++r) {
        const uint32_t b = random_bits<W>(rng, r);
        std::vector<int> visited;
        for_each_active(mask_from_bits<W>(b), [&](int lane) { visited.push_back(lane); });
        std::vector<int> want;
        for (int l = 0; l < W; ++l) {
            if ((b >> l) & 1u) want.push_back(l);
        }
        ASSERT_EQ(visited, want);
    }
}

// ---- compaction -----------------------------------------------------------------------------

TYPED_TEST(LanesTest, CompactKeepsLaneOrderAndZeroesTheRest) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(24);
    for (int r = 0; r < rounds; ++r) {
        const auto a = tagged_lanes<W>(rng);
        const uint32_t b = random_bits<W>(rng, r);
        const vmask<W> m = mask_from_bits<W>(b);
        std::array<float, W> got;
        std::array<int32_t, W> got_int;
        store(got.data(), compact(load<W>(a.data()), m));
        store(got_int.data(), compact(float_as_int(load<W>(a.data())), m));
        int n = 0;
        for (int l = 0; l < W; ++l) {
            if ((b >> l) & 1u) {
                ASSERT_EQ(bits_of(got[n]), bits_of(a[l])) << "output lane " << n;
                ASSERT_EQ(static_cast<uint32_t>(got_int[n]), bits_of(a[l]));
                ++n;
            }
        }
        for (int l = n; l < W; ++l) {
            ASSERT_EQ(bits_of(got[l]), 0u);
            ASSERT_EQ(got_int[l], 0);
        }
    }
}

TYPED_TEST(LanesTest, CompressStoreWritesExactlyTheActiveCount) {
    constexpr int W = TypeParam::value;
    constexpr uint32_t guard = 0xdeadbeefu;
    std::mt19937 rng(25);
    for (int r = 0; r < rounds; ++r) {
        const auto a = tagged_lanes<W>(rng);
        const uint32_t b = random_bits<W>(rng, r);
        const vmask<W> m = mask_from_bits<W>(b);
        const int offset = static_cast<int>(rng() % 3);  // unaligned destinations too
        std::array<float, W + 4> out;
        std::array<int32_t, W + 4> out_int;
        out.fill(std::bit_cast<float>(guard));
        out_int.fill(static_cast<int32_t>(guard));
        const int n = compress_store(out.data() + offset, load<W>(a.data()), m);
        const int n_int =
            compress_store(out_int.data() + offset, float_as_int(load<W>(a.data())), m);
        ASSERT_EQ(n, std::popcount(b));
        ASSERT_EQ(n_int, n);
        int k = offset;
        for (int l = 0; l < W; ++l) {
            if ((b >> l) & 1u) {
                ASSERT_EQ(bits_of(out[k]), bits_of(a[l]));
                ASSERT_EQ(static_cast<uint32_t>(out_int[k]), bits_of(a[l]));
                ++k;
            }
        }
        for (int i = 0; i < W + 4; ++i) {
            if (i >= offset && i < offset + n) continue;
            ASSERT_EQ(bits_of(out[i]), guard) << "wrote outside [offset, offset + n) at " << i;
            ASSERT_EQ(static_cast<uint32_t>(out_int[i]), guard);
        }
    }
}

// ---- masked memory --------------------------------------------------------------------------

TYPED_TEST(LanesTest, MaskedStoreLeavesInactiveLanesUntouched) {
    constexpr int W = TypeParam::value;
    constexpr uint32_t guard = 0xdeadbeefu;
    std::mt19937 rng(26);
    for (int r = 0; r < rounds; ++r) {
        const auto a = tagged_lanes<W>(rng);
        const uint32_t b = random_bits<W>(rng, r);
        std::array<float, W> out;
        std::array<int32_t, W> out_int;
        out.fill(std::bit_cast<float>(guard));
        out_int.fill(static_cast<int32_t>(guard));
        store(out.data(), load<W>(a.data()), mask_from_bits<W>(b));
        store(out_int.data(), float_as_int(load<W>(a.data())), mask_from_bits<W>(b));
        for (int l = 0; l < W; ++l) {
            const uint32_t want = (b >> l) & 1u ? bits_of(a[l]) : guard;
            ASSERT_EQ(bits_of(out[l]), want);
            ASSERT_EQ(static_cast<uint32_t>(out_int[l]), want);
        }
    }
}

TYPED_TEST(LanesTest, MaskedGatherNeverReadsInactiveIndices) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(27);
    std::vector<float> table(61);
    for (float& v : table) v = std::uniform_real_distribution<float>(-5.0f, 5.0f)(rng);
    for (int r = 0; r < rounds; ++r) {
        const uint32_t b = random_bits<W>(rng, r);
        std::array<int32_t, W> idx;
        for (int l = 0; l < W; ++l) {
            // an inactive lane's index points far outside the table: reading it would fault
            idx[l] = (b >> l) & 1u ? static_cast<int32_t>(rng() % 61) : (1 << 30) + l;
        }
        std::array<float, W> got;
        store(got.data(), gather(table.data(), load<W>(idx.data()), mask_from_bits<W>(b)));
        for (int l = 0; l < W; ++l) {
            const float want = (b >> l) & 1u ? table[static_cast<size_t>(idx[l])] : 0.0f;
            ASSERT_EQ(bits_of(got[l]), bits_of(want));
        }
    }
}

}  // namespace
}  // namespace raylane
