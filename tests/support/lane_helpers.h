// Test support: the helpers the simd tests share: a packet's lanes as an array, bit-exact float
// comparison, and random inputs with NaN, inf, -0.0 and denormals among them.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>

#include "simd/simd.h"

namespace raylane::test {

/// Random packets drawn per test by the tests of simd/.
inline constexpr int rounds = 2000;

inline uint32_t bits_of(float v) { return std::bit_cast<uint32_t>(v); }

/// Identical bits, or both NaN (payloads of generated NaNs are not specified).
inline bool same_float(float a, float b) {
    return (std::isnan(a) && std::isnan(b)) || bits_of(a) == bits_of(b);
}

/// The awkward values random_input draws from, and expect_binary_matches pairs exhaustively.
inline constexpr float input_specials[] = {0.0f,
                                           -0.0f,
                                           1.0f,
                                           -1.0f,
                                           std::numeric_limits<float>::infinity(),
                                           -std::numeric_limits<float>::infinity(),
                                           std::numeric_limits<float>::quiet_NaN(),
                                           -std::numeric_limits<float>::quiet_NaN(),
                                           std::numeric_limits<float>::denorm_min(),
                                           -std::numeric_limits<float>::denorm_min(),
                                           1e-40f,
                                           -1e-40f,
                                           -3e-39f,
                                           std::numeric_limits<float>::min(),
                                           std::numeric_limits<float>::max(),
                                           std::numeric_limits<float>::lowest(),
                                           0.5f,
                                           2.0f,
                                           3.0f,
                                           1e30f};

/// A mix of awkward values, random bit patterns and ordinary numbers.
inline float random_input(std::mt19937& rng) {
    switch (rng() % 4) {
        case 0:
            return input_specials[rng() % std::size(input_specials)];
        case 1:
            return std::bit_cast<float>(static_cast<uint32_t>(rng()));
        default:
            return std::uniform_real_distribution<float>(-100.0f, 100.0f)(rng);
    }
}

template <int W>
std::array<float, W> random_lanes(std::mt19937& rng) {
    std::array<float, W> a;
    for (float& v : a) v = random_input(rng);
    return a;
}

template <int W>
std::array<float, W> lanes_of(const vfloat<W>& v) {
    std::array<float, W> a;
    store(a.data(), v);
    return a;
}
template <int W>
std::array<int32_t, W> lanes_of(const vint<W>& v) {
    std::array<int32_t, W> a;
    store(a.data(), v);
    return a;
}

/// A mask's lanes as bools, read through select (lane access lives in lanes.h).
template <int W>
std::array<bool, W> mask_lanes(const vmask<W>& m) {
    const auto ones = lanes_of<W>(select(m, vfloat<W>(1.0f), vfloat<W>(0.0f)));
    std::array<bool, W> a;
    for (int l = 0; l < W; ++l) a[l] = ones[l] == 1.0f;
    return a;
}

/// Applies op to packets and oracle to their lanes; lanes must agree (same_float). The packets
/// hold every pair of input_specials first, W pairs at a time, then random inputs.
template <int W, class Op, class Oracle>
void expect_binary_matches(Op op, Oracle oracle, uint32_t seed) {
    auto check = [&](const std::array<float, W>& a, const std::array<float, W>& b) {
        const auto got = lanes_of<W>(op(load<W>(a.data()), load<W>(b.data())));
        for (int i = 0; i < W; ++i) {
            const float want = oracle(a[i], b[i]);
            ASSERT_TRUE(same_float(got[i], want))
                << "lane " << i << ": f(" << std::hexfloat << a[i] << ", " << b[i]
                << ") = " << got[i] << ", want " << want;
        }
    };
    constexpr size_t n = std::size(input_specials);
    for (size_t pair = 0; pair < n * n; pair += W) {
        std::array<float, W> a{}, b{};
        for (size_t i = 0; i < size_t(W); ++i) {
            const size_t k = (pair + i) % (n * n);
            a[i] = input_specials[k / n];
            b[i] = input_specials[k % n];
        }
        check(a, b);
        if (::testing::Test::HasFatalFailure()) return;
    }
    std::mt19937 rng(seed);
    for (int r = 0; r < rounds; ++r) {
        check(random_lanes<W>(rng), random_lanes<W>(rng));
        if (::testing::Test::HasFatalFailure()) return;
    }
}

}  // namespace raylane::test
