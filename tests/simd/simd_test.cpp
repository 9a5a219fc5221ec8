// tests for simd/simd.h: widths, memory, selection, mask logic, operators, int bit operations
// and conversions at every supported width, lane by lane against scalar C++ on random inputs
// that include NaN, inf, -0.0 and denormals.
#include "simd/simd.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>
#include <string>

#include "core/error.h"
#include "core/isa.h"
#include "support/lane_helpers.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

// ---- helpers ---------------------------------------------------------------------------------

template <class T>
class SimdTest : public ::testing::Test {};
TYPED_TEST_SUITE(SimdTest, Widths, WidthName);

// ---- widths ---------------------------------------------------------------------------------

TEST(SimdWidths, NativeWidthFollowsTheCompilerTarget) {
    EXPECT_TRUE(width_supported<native_width>);
    EXPECT_TRUE(width_supported<1>);
    EXPECT_FALSE(width_supported<2>);
#if defined(__AVX512F__)
    EXPECT_EQ(native_width, 16);
    EXPECT_TRUE(width_supported<8> && width_supported<4>);
#elif defined(__AVX2__)
    EXPECT_EQ(native_width, 8);
    EXPECT_FALSE(width_supported<16>);
#endif
    EXPECT_EQ(width_of<vfloat<native_width>>, native_width);
    EXPECT_EQ(width_of<vint<native_width>>, native_width);
    EXPECT_EQ(width_of<vmask<native_width>>, native_width);
    EXPECT_EQ(width_of<float>, 1);
}

TEST(SimdWidths, TheProgramsInstructionSetIsTheOneInUseAtItsWidth) {
    // test_main forces the set the program is compiled for; the dispatched functions use it
    EXPECT_EQ(active_isa(), Isa::RAYLANE_ISA_ENUM);
    EXPECT_EQ(isa_width(active_isa()), native_width);
    EXPECT_TRUE(cpu_runs(active_isa()));
    EXPECT_THROW(use_isa_named("avx1024", "test"), InputError);
    EXPECT_EQ(active_isa(), Isa::RAYLANE_ISA_ENUM);  // a refused name leaves the set as it was
}

TEST(SimdWidths, WidthOneIsPlainScalars) {
    EXPECT_TRUE((std::is_same_v<vfloat<1>, float>));
    EXPECT_TRUE((std::is_same_v<vint<1>, int32_t>));
    EXPECT_TRUE((std::is_same_v<vmask<1>, bool>));
}

// ---- construction and memory ----------------------------------------------------------------

TYPED_TEST(SimdTest, BroadcastFillsEveryLane) {
    constexpr int W = TypeParam::value;
    const auto f = lanes_of<W>(broadcast<W>(-0.0f));
    const auto i = lanes_of<W>(broadcast<W>(int32_t{-7}));
    const auto u = lanes_of<W>(broadcast<W>(0x9e3779b9u));
    for (int l = 0; l < W; ++l) {
        EXPECT_EQ(bits_of(f[l]), 0x80000000u);
        EXPECT_EQ(i[l], -7);
        EXPECT_EQ(static_cast<uint32_t>(u[l]), 0x9e3779b9u);
    }
}

TYPED_TEST(SimdTest, LoadsAndStoresRoundTripAlignedAndUnaligned) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(1);
    alignas(64) float src[W + 1];
    alignas(64) int32_t isrc[W + 1];
    for (int l = 0; l <= W; ++l) {
        src[l] = random_input(rng);
        isrc[l] = static_cast<int32_t>(rng());
    }
    alignas(64) float dst[W + 1] = {};
    alignas(64) int32_t idst[W + 1] = {};
    store_aligned(dst, load_aligned<W>(src));
    store_aligned(idst, load_aligned<W>(isrc));
    store(dst + 1, load<W>(src + 1));  // misaligned for W > 1
    store(idst + 1, load<W>(isrc + 1));
    for (int l = 0; l <= W; ++l) {
        EXPECT_EQ(bits_of(dst[l]), bits_of(src[l])) << l;
        EXPECT_EQ(idst[l], isrc[l]) << l;
    }
}

// ---- masks and selection --------------------------------------------------------------------

TYPED_TEST(SimdTest, SelectPassesOperandBitsThrough) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(3);
    for (int r = 0; r < rounds; ++r) {
        const auto a = random_lanes<W>(rng);
        const auto b = random_lanes<W>(rng);
        const auto c = random_lanes<W>(rng);
        const auto d = random_lanes<W>(rng);
        const vmask<W> m = load<W>(c.data()) < load<W>(d.data());
        const auto got = lanes_of<W>(select(m, load<W>(a.data()), load<W>(b.data())));
        const auto got_int = lanes_of<W>(
            select(m, float_as_int(load<W>(a.data())), float_as_int(load<W>(b.data()))));
        for (int l = 0; l < W; ++l) {
            const float want = c[l] < d[l] ? a[l] : b[l];
            ASSERT_EQ(bits_of(got[l]), bits_of(want));
            ASSERT_EQ(static_cast<uint32_t>(got_int[l]), bits_of(want));
        }
    }
}

TYPED_TEST(SimdTest, ComparisonsAndMaskLogicMatchScalarCpp) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(4);
    for (int r = 0; r < rounds; ++r) {
        const auto a = random_lanes<W>(rng);
        const auto b = random_lanes<W>(rng);
        const vfloat<W> va = load<W>(a.data());
        const vfloat<W> vb = load<W>(b.data());
        const vmask<W> p = va < vb;
        const vmask<W> q = va >= vfloat<W>(0.0f);
        const auto lt_lanes = mask_lanes<W>(p), ge0 = mask_lanes<W>(q);
        const auto both = mask_lanes<W>(mask_and(p, q)), either = mask_lanes<W>(mask_or(p, q));
        const auto p_not_q = mask_lanes<W>(mask_andnot(p, q)), not_p = mask_lanes<W>(mask_not(p));
        const auto equal = mask_lanes<W>(va == vb), le = mask_lanes<W>(va <= vb);
        const auto gt = mask_lanes<W>(va > vb);
        for (int l = 0; l < W; ++l) {
            const bool pl = a[l] < b[l];
            const bool ql = a[l] >= 0.0f;
            ASSERT_EQ(lt_lanes[l], pl);
            ASSERT_EQ(ge0[l], ql);
            ASSERT_EQ(both[l], pl && ql);
            ASSERT_EQ(either[l], pl || ql);
            ASSERT_EQ(p_not_q[l], pl && !ql);
            ASSERT_EQ(not_p[l], !pl);
            ASSERT_EQ(equal[l], a[l] == b[l]);
            ASSERT_EQ(le[l], a[l] <= b[l]);
            ASSERT_EQ(gt[l], a[l] > b[l]);
        }
    }
}

// ---- operators ------------------------------------------------------------------------------

TYPED_TEST(SimdTest, ArithmeticOperatorsAreCorrectlyRounded) {
    constexpr int W = TypeParam::value;
    // A double result rounded to float is correctly rounded for + - * / (53 >= 2 * 24 + 2).
    auto via_double = [](auto op) {
        return [op](float a, float b) { return static_cast<float>(op(double{a}, double{b})); };
    };
    expect_binary_matches<W>([](auto a, auto b) { return a + b; },
                             via_double([](double a, double b) { return a + b; }), 10);
    expect_binary_matches<W>([](auto a, auto b) { return a - b; },
                             via_double([](double a, double b) { return a - b; }), 11);
    expect_binary_matches<W>([](auto a, auto b) { return a * b; },
                             via_double([](double a, double b) { return a * b; }), 12);
    expect_binary_matches<W>([](auto a, auto b) { return a / b; },
                             via_double([](double a, double b) { return a / b; }), 9);
}

// ---- int32 lanes ----------------------------------------------------------------------------

TYPED_TEST(SimdTest, IntBitOpsAndComparisonsMatchScalarCpp) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(14);
    for (int r = 0; r < rounds; ++r) {
        std::array<int32_t, W> a, b;
        for (int l = 0; l < W; ++l) {
            a[l] = static_cast<int32_t>(rng());
            b[l] = r % 5 == 0 ? a[l] : static_cast<int32_t>(rng());
            if (r % 7 == 0) b[l] = std::numeric_limits<int32_t>::min();
        }
        const vint<W> va = load<W>(a.data());
        const vint<W> vb = load<W>(b.data());
        const auto x = lanes_of<W>(va ^ vb), n = lanes_of<W>(va & vb), o = lanes_of<W>(va | vb);
        const auto equal = mask_lanes<W>(eq(va, vb)), less = mask_lanes<W>(lt(va, vb));
        const auto greater = mask_lanes<W>(gt(va, vb));
        for (int l = 0; l < W; ++l) {
            ASSERT_EQ(x[l], a[l] ^ b[l]);
            ASSERT_EQ(n[l], a[l] & b[l]);
            ASSERT_EQ(o[l], a[l] | b[l]);
            ASSERT_EQ(equal[l], a[l] == b[l]);
            ASSERT_EQ(less[l], a[l] < b[l]);
            ASSERT_EQ(greater[l], a[l] > b[l]);
        }
    }
}

TYPED_TEST(SimdTest, UnsignedComparisonsReadIntLanesAsUint32) {
    constexpr int W = TypeParam::value;
    static constexpr uint32_t edges[] = {0u, 1u, 0x7fffffffu, 0x80000000u, 0x80000001u, ~0u};
    std::mt19937 rng(16);
    const auto draw = [&] {
        return static_cast<int32_t>(rng() % 3 == 0 ? edges[rng() % std::size(edges)] : rng());
    };
    for (int r = 0; r < rounds; ++r) {
        std::array<int32_t, W> a, b;
        for (int l = 0; l < W; ++l) {
            a[l] = draw();
            b[l] = r % 5 == 0 ? a[l] : draw();
        }
        const vint<W> va = load<W>(a.data());
        const vint<W> vb = load<W>(b.data());
        const auto less = mask_lanes<W>(lt_u32(va, vb));
        const auto less_equal = mask_lanes<W>(le_u32(va, vb));
        for (int l = 0; l < W; ++l) {
            const uint32_t ua = static_cast<uint32_t>(a[l]), ub = static_cast<uint32_t>(b[l]);
            ASSERT_EQ(less[l], ua < ub) << std::hex << ua << " < " << ub;
            ASSERT_EQ(less_equal[l], ua <= ub) << std::hex << ua << " <= " << ub;
        }
    }
}

// ---- conversions ----------------------------------------------------------------------------

TYPED_TEST(SimdTest, ConversionsRoundAndTruncateAsDocumented) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(15);
    for (int r = 0; r < rounds; ++r) {
        std::array<int32_t, W> counters, any;
        std::array<float, W> reals;
        for (int l = 0; l < W; ++l) {
            // lane 0 alternates between the two largest exact counters, 2^24 and 2^24 - 1
            counters[l] = static_cast<int32_t>(l == 0 ? (1u << 24) - static_cast<uint32_t>(r % 2)
                                                      : rng() % (1u << 24));
            any[l] = static_cast<int32_t>(rng());
            reals[l] = std::uniform_real_distribution<float>(-2.1e9f, 2.1e9f)(rng) /
                       static_cast<float>(1u << (rng() % 31));
        }
        const auto exact = lanes_of<W>(to_float(load<W>(counters.data())));
        const auto rounded = lanes_of<W>(to_float(load<W>(any.data())));
        const auto truncated = lanes_of<W>(to_int(load<W>(reals.data())));
        const auto as_int = lanes_of<W>(float_as_int(load<W>(reals.data())));
        const auto as_float = lanes_of<W>(int_as_float(load<W>(any.data())));
        for (int l = 0; l < W; ++l) {
            ASSERT_EQ(static_cast<double>(exact[l]), static_cast<double>(counters[l]));
            ASSERT_EQ(rounded[l], static_cast<float>(any[l]));
            ASSERT_EQ(truncated[l], static_cast<int32_t>(std::trunc(double{reals[l]})));
            ASSERT_EQ(static_cast<uint32_t>(as_int[l]), bits_of(reals[l]));
            ASSERT_EQ(bits_of(as_float[l]), static_cast<uint32_t>(any[l]));
        }
    }
    EXPECT_EQ(lanes_of<W>(to_int(vfloat<W>(-1.75f)))[0], -1);
    EXPECT_EQ(lanes_of<W>(to_float(vint<W>(1 << 24)))[0], 16777216.0f);
}

}  // namespace
}  // namespace raylane
