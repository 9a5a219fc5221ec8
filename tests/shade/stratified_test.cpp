// Stratified samples of the unit square (shade/lights_scalar.h, lights_packet.h): every count n
// is cut into n cells of equal area that tile the square, each sample stays in its cell, the
// estimator is unbiased and beats uniform sampling, and the packet path gives the same bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "shade/lights_packet.h"
#include "shade/lights_scalar.h"
#include "simd/lanes.h"
#include "support/widths.h"

namespace raylane {
namespace {

struct Cell {
    double x0, x1, y0, y1;
};

Cell cell_of(int i, int n) {
    const Stratum s = stratum_of(i, n);  // small integers: exact in float and double
    const double x0 = s.x0, cells = s.cells, row = s.row, count = s.n;
    return {x0 / count, (x0 + cells) / count, row / cells, (row + 1.0) / cells};
}

TEST(StratifiedSquare, CutsEveryCountIntoEqualCellsThatTileTheSquare) {
    for (int n = 1; n <= 200; ++n) {
        std::vector<Cell> cells;
        double area = 0.0;
        for (int i = 0; i < n; ++i) {
            const Cell c = cell_of(i, n);
            ASSERT_GE(c.x0, 0.0);
            ASSERT_LE(c.x1, 1.0);
            ASSERT_GE(c.y0, 0.0);
            ASSERT_LE(c.y1, 1.0);
            EXPECT_NEAR((c.x1 - c.x0) * (c.y1 - c.y0), 1.0 / n, 1e-9) << "n " << n << " i " << i;
            area += (c.x1 - c.x0) * (c.y1 - c.y0);
            cells.push_back(c);
        }
        EXPECT_NEAR(area, 1.0, 1e-9) << "n " << n;
        // no two cells overlap (with equal areas summing to 1, they tile the square)
        for (int a = 0; a < n; ++a)
            for (int b = a + 1; b < n; ++b) {
                const Cell& p = cells[static_cast<size_t>(a)];
                const Cell& q = cells[static_cast<size_t>(b)];
                const double w = std::min(p.x1, q.x1) - std::max(p.x0, q.x0);
                const double h = std::min(p.y1, q.y1) - std::max(p.y0, q.y0);
                ASSERT_FALSE(w > 1e-9 && h > 1e-9) << "n " << n << ": cells " << a << ", " << b;
            }
    }
}

TEST(StratifiedSquare, KeepsEverySampleInItsCell) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float ends[] = {0.0f, std::nextafter(1.0f, 0.0f)};
    for (int n = 1; n <= 70; ++n)
        for (int i = 0; i < n; ++i) {
            const Cell c = cell_of(i, n);
            for (int k = 0; k < 12; ++k) {
                const float u1 = k < 2 ? ends[k] : u(rng), u2 = k < 2 ? ends[1 - k] : u(rng);
                const vec2 p = stratified_square(i, n, u1, u2);
                const double slack = 1e-6;  // one rounding of a value below 1
                EXPECT_TRUE(p.x >= c.x0 - slack && p.x <= c.x1 + slack && p.y >= c.y0 - slack &&
                            p.y <= c.y1 + slack && p.x <= 1.0f && p.y <= 1.0f)
                    << "n " << n << " i " << i << ": (" << p.x << ", " << p.y << ")";
            }
        }
}

/// Mean and variance over `trials` of the n-sample estimate of the integral of x * y^2 (= 1/6).
std::pair<double, double> estimate(int n, int trials, bool stratified) {
    std::mt19937 rng(static_cast<uint32_t>(n));
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double sum = 0.0, sum2 = 0.0;
    for (int t = 0; t < trials; ++t) {
        double e = 0.0;
        for (int i = 0; i < n; ++i) {
            const float u1 = u(rng), u2 = u(rng);
            const vec2 p = stratified ? stratified_square(i, n, u1, u2) : vec2(u1, u2);
            e += double{p.x} * p.y * p.y;
        }
        e /= n;
        sum += e;
        sum2 += e * e;
    }
    const double mean = sum / trials;
    return {mean, sum2 / trials - mean * mean};
}

TEST(StratifiedSquare, IsUnbiasedAndBeatsUniformSamplingForCountsThatAreNotSquares) {
    for (int n : {2, 3, 5, 7, 12, 17}) {
        const int trials = 20000;
        const auto [mean, var] = estimate(n, trials, true);
        const auto [mean_u, var_u] = estimate(n, trials, false);
        EXPECT_NEAR(mean, 1.0 / 6.0, 5.0 * std::sqrt(var / trials)) << "n " << n;
        EXPECT_NEAR(mean_u, 1.0 / 6.0, 5.0 * std::sqrt(var_u / trials)) << "n " << n;
        // stratification of a smooth integrand: variance at least 1.5x lower (n^-1.5 vs n^-1)
        EXPECT_LT(var * 1.5, var_u) << "n " << n;
    }
}

template <class T>
class StratifiedSquarePacket : public ::testing::Test {};
TYPED_TEST_SUITE(StratifiedSquarePacket, Widths, WidthName);

TYPED_TEST(StratifiedSquarePacket, MatchesTheScalarBitForBit) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(5 + W);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int n = 1; n <= 40; ++n)
        for (int i = 0; i < n; ++i) {
            alignas(64) float u1[W], u2[W];
            for (int k = 0; k < W; ++k) u1[k] = u(rng), u2[k] = u(rng);
            vfloat<W> sx, sy;
            stratified_square<W>(i, n, load_aligned<W>(u1), load_aligned<W>(u2), sx, sy);
            for (int k = 0; k < W; ++k) {
                const vec2 p = stratified_square(i, n, u1[k], u2[k]);
                ASSERT_EQ(std::bit_cast<uint32_t>(get(sx, k)), std::bit_cast<uint32_t>(p.x));
                ASSERT_EQ(std::bit_cast<uint32_t>(get(sy, k)), std::bit_cast<uint32_t>(p.y));
            }
        }
}

}  // namespace
}  // namespace raylane
