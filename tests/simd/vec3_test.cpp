// tests for simd/vec3.h: Vec3<W> against glm::vec3 lane by lane, bit for bit (same operation
// order, no contraction), at every supported width.
#include "simd/vec3.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <random>
#include <string>

#include "support/lane_helpers.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

// ---- helpers ---------------------------------------------------------------------------------

template <class T>
class Vec3Test : public ::testing::Test {};
TYPED_TEST_SUITE(Vec3Test, Widths, WidthName);

/// W random vectors in SoA arrays; components span several magnitudes, some exactly zero.
template <int W>
struct SoA {
    std::array<float, W> x, y, z;
    glm::vec3 lane(int l) const { return {x[l], y[l], z[l]}; }
};
template <int W>
SoA<W> random_soa(std::mt19937& rng) {
    SoA<W> s;
    auto draw = [&] {
        if (rng() % 16 == 0) return 0.0f;
        const float m = std::uniform_real_distribution<float>(-1.0f, 1.0f)(rng);
        return std::ldexp(m, static_cast<int>(rng() % 41) - 20);
    };
    for (int l = 0; l < W; ++l) {
        s.x[l] = draw();
        s.y[l] = draw();
        s.z[l] = draw();
    }
    return s;
}
template <int W>
Vec3<W> load_soa(const SoA<W>& s) {
    return load_vec3<W>(s.x.data(), s.y.data(), s.z.data());
}
template <int W>
SoA<W> store_soa(const Vec3<W>& v) {
    SoA<W> s;
    store_vec3(s.x.data(), s.y.data(), s.z.data(), v);
    return s;
}

template <int W>
void expect_same(const SoA<W>& got, int l, glm::vec3 want, const char* what) {
    EXPECT_TRUE(same_float(got.x[l], want.x) && same_float(got.y[l], want.y) &&
                same_float(got.z[l], want.z))
        << what << " lane " << l << ": (" << got.x[l] << ", " << got.y[l] << ", " << got.z[l]
        << ") vs (" << want.x << ", " << want.y << ", " << want.z << ")";
}
// ---- tests ----------------------------------------------------------------------------------

TYPED_TEST(Vec3Test, DefaultIsZeroAndMakeBroadcasts) {
    constexpr int W = TypeParam::value;
    const auto zero = store_soa<W>(Vec3<W>{});
    const auto made = store_soa<W>(make_vec3<W>(1.0f, -2.0f, 0.5f));
    for (int l = 0; l < W; ++l) {
        expect_same<W>(zero, l, glm::vec3(0.0f), "default");
        expect_same<W>(made, l, glm::vec3(1.0f, -2.0f, 0.5f), "make_vec3");
    }
}

TYPED_TEST(Vec3Test, ArithmeticMatchesGlm) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(40);
    for (int r = 0; r < rounds; ++r) {
        const auto a = random_soa<W>(rng);
        const auto b = random_soa<W>(rng);
        const auto s = random_soa<W>(rng);
        const Vec3<W> va = load_soa(a), vb = load_soa(b);
        const vfloat<W> vs = load<W>(s.x.data());
        const auto sum = store_soa<W>(va + vb), diff = store_soa<W>(va - vb);
        const auto neg = store_soa<W>(-va), prod = store_soa<W>(va * vb);
        const auto scaled = store_soa<W>(va * vs), scaled_left = store_soa<W>(vs * va);
        const auto by_float = store_soa<W>(va * 0.25f), quot = store_soa<W>(va / vs);
        for (int l = 0; l < W; ++l) {
            const glm::vec3 ga = a.lane(l), gb = b.lane(l);
            expect_same<W>(sum, l, ga + gb, "+");
            expect_same<W>(diff, l, ga - gb, "-");
            expect_same<W>(neg, l, -ga, "unary -");
            expect_same<W>(prod, l, ga * gb, "*");
            expect_same<W>(scaled, l, ga * s.x[l], "* vfloat");
            expect_same<W>(scaled_left, l, s.x[l] * ga, "vfloat *");
            expect_same<W>(by_float, l, ga * 0.25f, "* float");
            expect_same<W>(quot, l, ga / s.x[l], "/");
        }
    }
}

TYPED_TEST(Vec3Test, GeometryMatchesGlmBitForBit) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(41);
    for (int r = 0; r < rounds; ++r) {
        const auto a = random_soa<W>(rng);
        const auto b = random_soa<W>(rng);
        const Vec3<W> va = load_soa(a), vb = load_soa(b);
        const auto d = lanes_of<W>(dot(va, vb));
        const auto len = lanes_of<W>(length(va));
        const auto c = store_soa<W>(cross(va, vb));
        const auto n = store_soa<W>(normalize(va));
        for (int l = 0; l < W; ++l) {
            const glm::vec3 ga = a.lane(l), gb = b.lane(l);
            ASSERT_TRUE(same_float(d[l], glm::dot(ga, gb))) << "dot lane " << l;
            ASSERT_TRUE(same_float(len[l], glm::length(ga))) << "length lane " << l;
            expect_same<W>(c, l, glm::cross(ga, gb), "cross");
            expect_same<W>(n, l, glm::normalize(ga), "normalize");
        }
    }
}

TYPED_TEST(Vec3Test, MinMaxAndSelectWorkPerComponent) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(42);
    for (int r = 0; r < rounds; ++r) {
        auto a = random_soa<W>(rng);
        const auto b = random_soa<W>(rng);
        a.y[0] = std::nanf("");  // NaN order: min / max return the second operand
        const Vec3<W> va = load_soa(a), vb = load_soa(b);
        const vmask<W> m = load<W>(a.x.data()) < load<W>(b.x.data());
        const auto lo = store_soa<W>(min(va, vb));
        const auto hi = store_soa<W>(max(va, vb));
        const auto sel = store_soa<W>(select(m, va, vb));
        for (int l = 0; l < W; ++l) {
            const glm::vec3 ga = a.lane(l), gb = b.lane(l);
            auto mn = [](float p, float q) { return p < q ? p : q; };
            auto mx = [](float p, float q) { return p > q ? p : q; };
            expect_same<W>(lo, l, {mn(ga.x, gb.x), mn(ga.y, gb.y), mn(ga.z, gb.z)}, "min");
            expect_same<W>(hi, l, {mx(ga.x, gb.x), mx(ga.y, gb.y), mx(ga.z, gb.z)}, "max");
            expect_same<W>(sel, l, a.x[l] < b.x[l] ? ga : gb, "select");
        }
        EXPECT_EQ(lo.y[0], b.y[0]);
    }
}

TYPED_TEST(Vec3Test, StoreAosWritesTheVectorsAsTriples) {
    constexpr int W = TypeParam::value;
    constexpr uint32_t guard = 0xdeadbeefu;
    std::mt19937 rng(31);
    for (int r = 0; r < rounds; ++r) {
        SoA<W> s = random_soa<W>(rng);
        s.x[0] = std::bit_cast<float>(0x7fc01234u);  // a NaN payload and -0.0 kept bit for bit
        s.z[W - 1] = -0.0f;
        std::array<float, 3 * W + 2> out;
        out.fill(std::bit_cast<float>(guard));
        store_vec3_aos(out.data() + 1, load_soa(s));  // any alignment
        ASSERT_EQ(bits_of(out[0]), guard);
        ASSERT_EQ(bits_of(out[3 * W + 1]), guard);
        for (int l = 0; l < W; ++l) {
            ASSERT_EQ(bits_of(out[1 + 3 * l]), bits_of(s.x[l])) << "lane " << l;
            ASSERT_EQ(bits_of(out[2 + 3 * l]), bits_of(s.y[l])) << "lane " << l;
            ASSERT_EQ(bits_of(out[3 + 3 * l]), bits_of(s.z[l])) << "lane " << l;
        }
    }
}

}  // namespace
}  // namespace raylane
