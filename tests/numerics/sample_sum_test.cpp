// numerics.md §19: accumulating many samples. The film's compensated pixel sums
// (render/sample_sum_scalar.h, sample_sum_packet.h) keep 1e8 samples to a relative error below
// 1e-6 where a plain float sum loses most of the total, and both paths give the same bits.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "image/film.h"
#include "render/sample_sum_packet.h"
#include "render/sample_sum_scalar.h"
#include "report/report_metrics.h"
#include "simd/lanes.h"
#include "support/widths.h"

namespace raylane {
namespace {

#ifdef RAYLANE_SANITIZED
constexpr int32_t many = 20'000'000;  // still past 2^24 additions
#else
constexpr int32_t many = 100'000'000;
#endif

TEST(PixelSum, KeepsOneHundredMillionSamplesToOnePartInAMillion) {
    PixelSum p;
    float plain = 0.0f;  // what a naive float accumulator does with the same samples
    for (int32_t i = 0; i < many; ++i) {
        add_sample(p, vec3(0.1f, 0.7f, 3.0f));
        plain += 0.1f;
    }
    const vec3 mean = pixel_mean(p);
    EXPECT_EQ(p.count, many);
    EXPECT_LT(std::fabs(mean.x - 0.1) / 0.1, 1e-6);
    EXPECT_LT(std::fabs(mean.y - 0.7) / 0.7, 1e-6);
    EXPECT_LT(std::fabs(mean.z - 3.0) / 3.0, 1e-6);
    // the test can fail: without compensation the mean is far off
    EXPECT_GT(std::fabs(plain / static_cast<float>(many) - 0.1) / 0.1, 1e-2);
}

TEST(PixelSum, MeanOfNoSamplesIsZero) {
    const vec3 m = pixel_mean(PixelSum{});
    EXPECT_EQ(m, vec3(0.0f));
}

TEST(PixelSum, MatchesADoubleSumOfRandomSamples) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    PixelSum p;
    double exact = 0.0;
    const int n = 1 << 22;
    for (int i = 0; i < n; ++i) {
        // a heavy tail: most samples small, a few fireflies
        const float v = u(rng) < 0.001f ? 1000.0f * u(rng) : u(rng);
        add_sample(p, vec3(v));
        exact += v;
    }
    EXPECT_LT(std::fabs(pixel_mean(p).x - exact / n) / (exact / n), 1e-6);
}

template <class T>
class PixelSumPacketTest : public ::testing::Test {};
TYPED_TEST_SUITE(PixelSumPacketTest, Widths, WidthName);

TYPED_TEST(PixelSumPacketTest, GivesEveryLaneTheScalarBits) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(17 + W);
    std::uniform_real_distribution<float> u(0.0f, 10.0f);
    PixelSumPacket<W> packet;
    PixelSum scalar[W];
    for (int s = 0; s < 100000; ++s) {
        alignas(64) float x[W], y[W], z[W];
        const uint32_t bits = static_cast<uint32_t>(rng());
        for (int i = 0; i < W; ++i) x[i] = u(rng), y[i] = u(rng) * 1e-3f, z[i] = u(rng) * 1e3f;
        add_sample<W>(packet, load_vec3<W>(x, y, z), mask_from_bits<W>(bits));
        for (int i = 0; i < W; ++i)
            if (bits >> i & 1u) add_sample(scalar[i], vec3(x[i], y[i], z[i]));
    }
    const Vec3<W> mean = pixel_mean<W>(packet);
    for (int i = 0; i < W; ++i) {
        const vec3 want = pixel_mean(scalar[i]);
        EXPECT_EQ(std::bit_cast<uint32_t>(get(mean.x, i)), std::bit_cast<uint32_t>(want.x));
        EXPECT_EQ(std::bit_cast<uint32_t>(get(mean.y, i)), std::bit_cast<uint32_t>(want.y));
        EXPECT_EQ(std::bit_cast<uint32_t>(get(mean.z, i)), std::bit_cast<uint32_t>(want.z));
        EXPECT_EQ(get(packet.count, i), scalar[i].count);
    }
}

/// numerics.md §19: the error metrics of a 4K image (3840 x 2160 x 3 values) whose error is the
/// same everywhere come out as that error to one part in a billion: summing 2.5e7 equal squares
/// must not drift. The error is the float difference itself, so the expected values are exact.
TEST(ErrorMetricSum, FourKImageOfConstantErrorIsExactToOnePartInABillion) {
    Film reference = make_film(3840, 2160), image = make_film(3840, 2160);
    for (vec3& p : reference.pixels) p = vec3(0.5f, 0.25f, 2.0f);
    for (vec3& p : image.pixels) p = vec3(0.501f, 0.251f, 2.001f);
    const ErrorMetrics m = compute_error(image, reference);
    double mse = 0.0, rel = 0.0;
    for (int c = 0; c < 3; ++c) {
        const double d = double(image.pixels[0][c]) - double(reference.pixels[0][c]);
        const double r = reference.pixels[0][c];
        mse += d * d / 3.0;
        rel += d * d / (r * r + relmse_epsilon) / 3.0;
    }
    EXPECT_NEAR(m.mse, mse, 1e-9 * mse);
    EXPECT_NEAR(m.rmse, std::sqrt(mse), 1e-9 * std::sqrt(mse));
    EXPECT_NEAR(m.relmse, rel, 1e-9 * rel);
    std::printf("4K constant error: rmse relative error %.3g\n",
                std::fabs(m.rmse - std::sqrt(mse)) / std::sqrt(mse));
}

}  // namespace
}  // namespace raylane
