// tests for simd/hash.h: the packet hash is bit-identical to core/rng.h on every lane, at every
// supported width.
#include "simd/hash.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <string>

#include "core/rng.h"
#include "simd/lanes.h"  // lane_index
#include "support/lane_helpers.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

template <class T>
class HashTest : public ::testing::Test {};
TYPED_TEST_SUITE(HashTest, Widths, WidthName);

constexpr uint32_t hash_counters = 100000;

/// Counter c's four inputs: consecutive pixels, samples and dims that vary, large seeds, so every
/// bit of the inputs (including the sign bit of an int32 lane) gets exercised.
struct Counters {
    uint32_t pixel, sample, dim, seed;
};
Counters counters_for(uint32_t c) {
    return {c * 2654435761u, c / 7, c % 11, 0x80000000u ^ (c >> 3)};
}

TYPED_TEST(HashTest, MatchesScalarRngBitForBit) {
    constexpr int W = TypeParam::value;
    for (uint32_t base = 0; base < hash_counters; base += W) {
        std::array<int32_t, W> pixel, sample, dim, seed;
        for (int l = 0; l < W; ++l) {
            const Counters c = counters_for(base + static_cast<uint32_t>(l));
            pixel[l] = static_cast<int32_t>(c.pixel);
            sample[l] = static_cast<int32_t>(c.sample);
            dim[l] = static_cast<int32_t>(c.dim);
            seed[l] = static_cast<int32_t>(c.seed);
        }
        const vint<W> p = load<W>(pixel.data()), s = load<W>(sample.data());
        const vint<W> d = load<W>(dim.data()), e = load<W>(seed.data());
        const auto h = lanes_of<W>(hash_u32<W>(p));
        const auto hs = lanes_of<W>(hash_sample<W>(p, s, d, e));
        std::array<float, W> f;
        store(f.data(), random_float<W>(p, s, d, e));
        for (int l = 0; l < W; ++l) {
            const Counters c = counters_for(base + static_cast<uint32_t>(l));
            ASSERT_EQ(static_cast<uint32_t>(h[l]), hash_u32(c.pixel)) << "counter " << base + l;
            ASSERT_EQ(static_cast<uint32_t>(hs[l]), hash_sample(c.pixel, c.sample, c.dim, c.seed));
            const float want = random_float(c.pixel, c.sample, c.dim, c.seed);
            ASSERT_EQ(std::bit_cast<uint32_t>(f[l]), std::bit_cast<uint32_t>(want));
            ASSERT_GE(f[l], 0.0f);
            ASSERT_LT(f[l], 1.0f);
        }
    }
}

TYPED_TEST(HashTest, AcceptsBroadcastDimensionAndSeed) {
    constexpr int W = TypeParam::value;
    const vint<W> pixel = lane_index<W>();
    const auto got = lanes_of<W>(hash_sample<W>(pixel, broadcast<W>(3u), dim_lens_u, 0xfeedbeefu));
    for (int l = 0; l < W; ++l) {
        EXPECT_EQ(static_cast<uint32_t>(got[l]),
                  hash_sample(static_cast<uint32_t>(l), 3u, dim_lens_u, 0xfeedbeefu));
    }
}

}  // namespace
}  // namespace raylane
