// tests for simd/math.h at every supported width against scalar oracles: min/max NaN order, neg,
// wrapping ints, uint32 min/max, fma, reciprocals, sign bits, masked reductions; and the
// contraction canary.
#include "simd/math.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>
#include <string>

#include "simd/lanes.h"  // get, lane_index, mask_from_bits
#include "support/lane_helpers.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

constexpr float inf = std::numeric_limits<float>::infinity();

// ---- helpers ---------------------------------------------------------------------------------

template <class T>
class MathTest : public ::testing::Test {};
TYPED_TEST_SUITE(MathTest, Widths, WidthName);

/// The SSE instructions themselves, as the oracle for the documented min / max semantics.
float sse_min(float a, float b) { return _mm_cvtss_f32(_mm_min_ss(_mm_set_ss(a), _mm_set_ss(b))); }
float sse_max(float a, float b) { return _mm_cvtss_f32(_mm_max_ss(_mm_set_ss(a), _mm_set_ss(b))); }

// ---- contraction canary ---------------------------------------------------------------------

TEST(Contraction, IsOffInThisBuild) {
    // With a*b - c*d contracted to fma(a, b, -c*d) the result is 2^-24; without, exactly 0.
    volatile float va = 1.0f + 0x1.0p-12f, vb = va, vc = va, vd = va;
    const float a = va, b = vb, c = vc, d = vd;
    EXPECT_EQ(a * b - c * d, 0.0f) << "-ffp-contract=off is not in effect (numerics.md §0.2)";
}

// ---- basic float functions ------------------------------------------------------------------

TYPED_TEST(MathTest, MinAndMaxFollowTheSseOperandOrderForNanAndZeros) {
    constexpr int W = TypeParam::value;
    expect_binary_matches<W>([](auto a, auto b) { return min(a, b); }, sse_min, 5);
    expect_binary_matches<W>([](auto a, auto b) { return max(a, b); }, sse_max, 6);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const vfloat<W> five(5.0f);
    EXPECT_EQ(get(min(vfloat<W>(nan), five), 0), 5.0f);
    EXPECT_TRUE(std::isnan(get(min(five, vfloat<W>(nan)), 0)));
    EXPECT_EQ(get(max(vfloat<W>(nan), five), 0), 5.0f);
    EXPECT_EQ(bits_of(get(min(vfloat<W>(-0.0f), vfloat<W>(0.0f)), 0)), 0u);
}

TYPED_TEST(MathTest, AbsClearsOnlyTheSignBit) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(7);
    for (int r = 0; r < rounds; ++r) {
        const auto a = random_lanes<W>(rng);
        const auto got = lanes_of<W>(abs(load<W>(a.data())));
        for (int l = 0; l < W; ++l) ASSERT_EQ(bits_of(got[l]), bits_of(a[l]) & 0x7fffffffu);
    }
}

TYPED_TEST(MathTest, SqrtIsCorrectlyRounded) {
    constexpr int W = TypeParam::value;
    // A double square root rounded to float is correctly rounded (53 >= 2 * 24 + 2).
    expect_binary_matches<W>(
        [](auto a, auto) { return sqrt(a); },
        [](float a, float) { return static_cast<float>(std::sqrt(double{a})); }, 8);
    EXPECT_EQ(bits_of(get(sqrt(vfloat<W>(-0.0f)), 0)), 0x80000000u);
}

TYPED_TEST(MathTest, NegFlipsTheSignBitOfZerosAndNans) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(13);
    for (int r = 0; r < rounds; ++r) {
        const auto a = random_lanes<W>(rng);
        const auto got = lanes_of<W>(neg(load<W>(a.data())));
        for (int l = 0; l < W; ++l) ASSERT_EQ(bits_of(got[l]), bits_of(a[l]) ^ 0x80000000u);
    }
}

TYPED_TEST(MathTest, NeAndIsNanTreatNanAsCppDoes) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(16);
    for (int r = 0; r < rounds; ++r) {
        const auto a = random_lanes<W>(rng);
        const auto b = random_lanes<W>(rng);
        const vfloat<W> va = load<W>(a.data()), vb = load<W>(b.data());
        for (int l = 0; l < W; ++l) {
            ASSERT_EQ(get(ne(va, vb), l), a[l] != b[l]);
            ASSERT_EQ(get(ne(va, va), l), std::isnan(a[l]));
            ASSERT_EQ(get(is_nan(va), l), std::isnan(a[l]));
        }
    }
}

// ---- int32 arithmetic -----------------------------------------------------------------------

TYPED_TEST(MathTest, IntArithmeticWrapsLikeUint32) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(14);
    for (int r = 0; r < rounds; ++r) {
        std::array<int32_t, W> a, b;
        for (int l = 0; l < W; ++l) {
            a[l] = static_cast<int32_t>(rng());
            b[l] = r % 7 == 0 ? std::numeric_limits<int32_t>::min() : static_cast<int32_t>(rng());
        }
        const vint<W> va = load<W>(a.data());
        const vint<W> vb = load<W>(b.data());
        const auto sum = lanes_of<W>(add(va, vb));
        const auto prod = lanes_of<W>(mul_lo(va, vb));
        const auto sl = lanes_of<W>(shift_left<7>(va));
        const auto srl = lanes_of<W>(shift_right_logical<13>(va));
        const auto srl31 = lanes_of<W>(shift_right_logical<31>(va));
        const auto sra = lanes_of<W>(shift_right_arith<13>(va));
        for (int l = 0; l < W; ++l) {
            const uint32_t ua = static_cast<uint32_t>(a[l]);
            const uint32_t ub = static_cast<uint32_t>(b[l]);
            ASSERT_EQ(static_cast<uint32_t>(sum[l]), ua + ub);
            ASSERT_EQ(static_cast<uint32_t>(prod[l]), ua * ub);
            ASSERT_EQ(static_cast<uint32_t>(sl[l]), ua << 7);
            ASSERT_EQ(static_cast<uint32_t>(srl[l]), ua >> 13);
            ASSERT_EQ(static_cast<uint32_t>(srl31[l]), ua >> 31);
            // arithmetic shift: floor division by 2^13
            ASSERT_EQ(sra[l], static_cast<int32_t>(std::floor(static_cast<double>(a[l]) / 8192.0)));
        }
    }
}

// ---- uint32 order ----------------------------------------------------------------------------

/// Random uint32 lane bits, a third of them at the edges of the signed and unsigned orders.
template <int W>
std::array<int32_t, W> uint32_lanes(std::mt19937& rng) {
    static constexpr uint32_t edges[] = {0u, 1u, 0x7fffffffu, 0x80000000u, 0x80000001u, ~0u};
    std::array<int32_t, W> a;
    for (int32_t& v : a)
        v = static_cast<int32_t>(rng() % 3 == 0 ? edges[rng() % std::size(edges)] : rng());
    return a;
}

TYPED_TEST(MathTest, Uint32MinAndMaxOrderLanesAsUnsigned) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(30);
    for (int r = 0; r < rounds; ++r) {
        const auto a = uint32_lanes<W>(rng);
        auto b = uint32_lanes<W>(rng);
        if (r % 5 == 0) b = a;
        // every 8th mask all-off, every 8th (offset) all-on
        const uint32_t active = r % 8 == 0 ? 0u : (r % 8 == 4 ? ~0u : static_cast<uint32_t>(rng()));
        const vint<W> va = load<W>(a.data());
        const vint<W> vb = load<W>(b.data());
        const vmask<W> m = mask_from_bits<W>(active);
        const auto lo = lanes_of<W>(min_u32(va, vb)), hi = lanes_of<W>(max_u32(va, vb));
        const auto masked_lo = lanes_of<W>(min_u32(va, vb, m));
        const auto masked_hi = lanes_of<W>(max_u32(va, vb, m));
        for (int l = 0; l < W; ++l) {
            const uint32_t ua = static_cast<uint32_t>(a[l]), ub = static_cast<uint32_t>(b[l]);
            const bool on = (active >> l) & 1u;
            ASSERT_EQ(static_cast<uint32_t>(lo[l]), std::min(ua, ub));
            ASSERT_EQ(static_cast<uint32_t>(hi[l]), std::max(ua, ub));
            ASSERT_EQ(static_cast<uint32_t>(masked_lo[l]), on ? std::min(ua, ub) : ua);
            ASSERT_EQ(static_cast<uint32_t>(masked_hi[l]), on ? std::max(ua, ub) : ua);
        }
    }
}

TYPED_TEST(MathTest, Uint32ReductionsFindTheSmallestAndLargestLane) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(31);
    for (int r = 0; r < rounds; ++r) {
        const auto a = uint32_lanes<W>(rng);
        uint32_t want_lo = ~0u, want_hi = 0u;
        for (const int32_t v : a) {
            want_lo = std::min(want_lo, static_cast<uint32_t>(v));
            want_hi = std::max(want_hi, static_cast<uint32_t>(v));
        }
        ASSERT_EQ(hmin_u32(load<W>(a.data())), want_lo);
        ASSERT_EQ(hmax_u32(load<W>(a.data())), want_hi);
    }
}

// ---- fused multiply-add ---------------------------------------------------------------------

TYPED_TEST(MathTest, FmaRoundsOnce) {
    constexpr int W = TypeParam::value;
    // (1 + 2^-12)^2 = 1 + 2^-11 + 2^-24: the 2^-24 survives only without an intermediate rounding.
    const vfloat<W> a(1.0f + 0x1.0p-12f);
    const vfloat<W> c(-(1.0f + 0x1.0p-11f));
    const auto fused = lanes_of<W>(fma(a, a, c));
    const auto unfused = lanes_of<W>(a * a + c);
    for (int l = 0; l < W; ++l) {
        EXPECT_EQ(fused[l], 0x1.0p-24f);
        EXPECT_EQ(unfused[l], 0.0f);
    }
}

TYPED_TEST(MathTest, FmaMatchesStdFmaOnEveryLane) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(30);
    for (int r = 0; r < rounds; ++r) {
        const auto a = random_lanes<W>(rng);
        const auto b = random_lanes<W>(rng);
        const auto c = random_lanes<W>(rng);
        const auto got = lanes_of<W>(fma(load<W>(a.data()), load<W>(b.data()), load<W>(c.data())));
        for (int l = 0; l < W; ++l) {
            ASSERT_TRUE(same_float(got[l], std::fma(a[l], b[l], c[l])))
                << std::hexfloat << a[l] << " " << b[l] << " " << c[l];
        }
    }
}

// ---- reciprocals ----------------------------------------------------------------------------

TYPED_TEST(MathTest, RcpExactIsCorrectlyRoundedDivision) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(31);
    for (int r = 0; r < rounds; ++r) {
        const auto a = random_lanes<W>(rng);
        const auto got = lanes_of<W>(rcp_exact(load<W>(a.data())));
        for (int l = 0; l < W; ++l) {
            ASSERT_TRUE(same_float(got[l], static_cast<float>(1.0 / double{a[l]}))) << a[l];
        }
    }
    EXPECT_EQ(get(rcp_exact(vfloat<W>(-0.0f)), 0), -inf);
    EXPECT_EQ(bits_of(get(rcp_exact(vfloat<W>(-inf)), 0)), 0x80000000u);
}

TYPED_TEST(MathTest, RcpRefinedIsCloseButOnlyApproximate) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(32);
    double worst = 0.0;
    for (int r = 0; r < rounds; ++r) {
        std::array<float, W> a;
        for (float& v : a) {
            // normal inputs with normal reciprocals: |v| in [2^-125, 2^125]
            const float mantissa = std::uniform_real_distribution<float>(1.0f, 2.0f)(rng);
            v = std::ldexp(rng() % 2 ? mantissa : -mantissa, static_cast<int>(rng() % 251) - 125);
        }
        const auto got = lanes_of<W>(rcp_refined(load<W>(a.data())));
        for (int l = 0; l < W; ++l) {
            const double exact = 1.0 / double{a[l]};
            const double rel = std::abs((double{got[l]} - exact) / exact);
            ASSERT_LT(rel, 0x1.0p-21) << std::hexfloat << a[l];
            worst = std::max(worst, rel);
        }
    }
    EXPECT_GT(worst, 0.0) << "suspiciously exact: is rcp_refined a division?";
    const vfloat<W> zeros(0.0f);
    EXPECT_EQ(get(rcp_refined(zeros), 0), inf);
    EXPECT_EQ(get(rcp_refined(vfloat<W>(-0.0f)), 0), -inf);
    EXPECT_EQ(bits_of(get(rcp_refined(vfloat<W>(inf)), 0)), 0u);
    EXPECT_EQ(bits_of(get(rcp_refined(vfloat<W>(-inf)), 0)), 0x80000000u);
}

// ---- sign bits ------------------------------------------------------------------------------

TYPED_TEST(MathTest, SignBitOpsMatchTheScalarLibrary) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(33);
    for (int r = 0; r < rounds; ++r) {
        const auto a = random_lanes<W>(rng);
        const auto s = random_lanes<W>(rng);
        const vfloat<W> va = load<W>(a.data());
        const vfloat<W> vs = load<W>(s.data());
        const auto cs = lanes_of<W>(copysign(va, vs));
        const auto ms = lanes_of<W>(mul_sign(va, vs));
        for (int l = 0; l < W; ++l) {
            ASSERT_EQ(get(sign_bit(vs), l), std::signbit(s[l]));
            ASSERT_EQ(bits_of(cs[l]), bits_of(std::copysign(a[l], s[l])));
            const uint32_t flipped = bits_of(a[l]) ^ (bits_of(s[l]) & 0x80000000u);
            ASSERT_EQ(bits_of(ms[l]), flipped);
            // the multiply agrees except on denormals, which the test harness flushes (DAZ)
            if (!std::isnan(a[l]) && !std::isnan(s[l]) && s[l] != 0.0f &&
                (bits_of(a[l]) & 0x7f800000u) != 0u) {
                ASSERT_EQ(bits_of(ms[l]), bits_of(a[l] * (s[l] < 0.0f ? -1.0f : 1.0f)));
            }
        }
    }
}

// ---- horizontal reductions ------------------------------------------------------------------

TYPED_TEST(MathTest, MaskedMinAndMaxIgnoreInactiveAndNanLanes) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(34);
    for (int r = 0; r < rounds; ++r) {
        const auto a = random_lanes<W>(rng);
        const uint32_t b = r % 8 == 0 ? 0u : static_cast<uint32_t>(rng()) | (r % 8 == 4 ? ~0u : 0u);
        float lo = inf;
        float hi = -inf;
        for (int l = 0; l < W; ++l) {
            if (((b >> l) & 1u) && !std::isnan(a[l])) {
                lo = std::fmin(lo, a[l]);
                hi = std::fmax(hi, a[l]);
            }
        }
        const vfloat<W> v = load<W>(a.data());
        const vmask<W> m = mask_from_bits<W>(b);
        ASSERT_EQ(hmin(v, m), lo);  // == accepts either zero when -0.0 and +0.0 tie
        ASSERT_EQ(hmax(v, m), hi);
        if (b == 0) {
            ASSERT_EQ(hmin(v, m), inf);
            ASSERT_EQ(hmax(v, m), -inf);
        }
    }
}

TYPED_TEST(MathTest, UnmaskedReductionsUseEveryLane) {
    constexpr int W = TypeParam::value;
    const vfloat<W> v = to_float(lane_index<W>()) - vfloat<W>(2.0f);
    EXPECT_EQ(hmin(v), -2.0f);
    EXPECT_EQ(hmax(v), static_cast<float>(W - 3));
    EXPECT_EQ(hsum(v), static_cast<float>(W * (W - 1) / 2 - 2 * W));
}

TYPED_TEST(MathTest, MaskedSumAddsOnlyActiveLanes) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(35);
    for (int r = 0; r < rounds; ++r) {
        // small integers and halves: every partial sum is exact, so the order cannot matter
        std::array<float, W> a;
        for (float& v : a) v = static_cast<float>(static_cast<int>(rng() % 2001) - 1000) * 0.5f;
        const uint32_t b = r % 8 == 0 ? 0u : static_cast<uint32_t>(rng());
        a[0] = b & 1u ? a[0] : std::numeric_limits<float>::quiet_NaN();  // inactive NaN is ignored
        float want = 0.0f;
        for (int l = 0; l < W; ++l) want += (b >> l) & 1u ? a[l] : 0.0f;
        ASSERT_EQ(hsum(load<W>(a.data()), mask_from_bits<W>(b)), want);
    }
}

}  // namespace
}  // namespace raylane
