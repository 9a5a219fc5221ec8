// image: the 8-bit encoding of a linear channel (film.h encode_channel): clamped, sRGB or
// linear, rounded; NaN and infinities never reach the byte cast (numerics.md section 18). The
// table that gives the same sRGB bytes (SrgbTable) and a whole film's bytes (encode_film).
#include "image/film.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace raylane {
namespace {

TEST(EncodeChannel, ClampsAndRoundsLinearValues) {
    EXPECT_EQ(encode_channel(0.0f, Encoding::linear), 0);
    EXPECT_EQ(encode_channel(1.0f, Encoding::linear), 255);
    EXPECT_EQ(encode_channel(-3.0f, Encoding::linear), 0);
    EXPECT_EQ(encode_channel(7.0f, Encoding::linear), 255);
    EXPECT_EQ(encode_channel(0.5f, Encoding::linear), 128);  // 127.5 rounds half up
    EXPECT_EQ(encode_channel(100.0f / 255.0f, Encoding::linear), 100);
}

TEST(EncodeChannel, AppliesTheSrgbCurve) {
    // sRGB(0.5) = 1.055 0.5^(1/2.4) - 0.055 = 0.7354 -> 188; the linear toe below 0.0031308
    EXPECT_EQ(encode_channel(0.5f, Encoding::srgb), 188);
    EXPECT_EQ(encode_channel(0.003f, Encoding::srgb), 10);  // 12.92 * 0.003 * 255 = 9.88
    EXPECT_EQ(encode_channel(1.0f, Encoding::srgb), 255);
    EXPECT_EQ(encode_channel(0.0f, Encoding::srgb), 0);
}

TEST(EncodeChannel, NonFiniteValuesBecomeBlack) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (Encoding e : {Encoding::linear, Encoding::srgb}) {
        EXPECT_EQ(encode_channel(nan, e), 0);
        EXPECT_EQ(encode_channel(-nan, e), 0);
        EXPECT_EQ(encode_channel(inf, e), 0);
        EXPECT_EQ(encode_channel(-inf, e), 0);
    }
}

// The table must give encode_channel's byte for every float. Checked here: non-decreasing on a
// sample (the bisection that finds the steps assumes it), every step and the float below it,
// the first and last float of every bucket, a sample of 4.2 million floats of [0, 1], and the
// values outside it. (All 2^30 floats of [0, 1] were checked once: the same bytes.)
TEST(SrgbTable, GivesEncodeChannelsByte) {
    const SrgbTable& table = srgb_table();
    auto srgb = [](uint32_t bits) {
        return encode_channel(std::bit_cast<float>(bits), Encoding::srgb);
    };
    auto fast = [&](uint32_t bits) { return table(std::bit_cast<float>(bits)); };
    int previous = 0;
    for (uint32_t b = 0; b <= SrgbTable::one_bits; b += 251) {
        ASSERT_LE(previous, srgb(b)) << b;
        previous = srgb(b);
        ASSERT_EQ(fast(b), srgb(b)) << b;
    }
    for (int k = 1; k <= 255; ++k) {
        const uint32_t b = std::bit_cast<uint32_t>(table.step[k]);
        ASSERT_EQ(srgb(b), k);
        ASSERT_EQ(srgb(b - 1), k - 1);
        ASSERT_EQ(fast(b), k);
        ASSERT_EQ(fast(b - 1), k - 1);
    }
    for (uint32_t bucket = 0; bucket < SrgbTable::buckets; ++bucket) {
        const uint32_t first = bucket << SrgbTable::shift;
        const uint32_t last = std::min(first + (1u << SrgbTable::shift) - 1u, SrgbTable::one_bits);
        ASSERT_EQ(fast(first), srgb(first)) << bucket;
        ASSERT_EQ(fast(last), srgb(last)) << bucket;
    }
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (float x : {-0.0f, nan, -nan, inf, -inf, -1.0f, -1e-30f, 1.0f, 1.0000001f, 2.0f, 1e30f,
                    std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::min(),
                    0.0031308f, 0.5f})
        EXPECT_EQ(table(x), encode_channel(x, Encoding::srgb)) << x;
}

TEST(EncodeFilm, EncodesEveryChannelOfEveryRow) {
    Film film = make_film(7, 5);
    for (int y = 0; y < film.height; ++y)
        for (int x = 0; x < film.width; ++x)
            film.at(x, y) = vec3(0.13f * float(x) - 0.1f, 0.21f * float(y), float(x * y) / 20.0f);
    film.at(3, 2) = vec3(std::numeric_limits<float>::quiet_NaN(), -0.0f, 7.0f);
    for (Encoding e : {Encoding::srgb, Encoding::linear}) {
        const ImageBytes bytes = encode_film(film, e);
        ASSERT_EQ(bytes.size(), size_t(7 * 5 * 3));
        for (int y = 0; y < film.height; ++y)
            for (int x = 0; x < film.width; ++x)
                for (int c = 0; c < 3; ++c)
                    EXPECT_EQ(bytes[size_t(3 * (y * film.width + x) + c)],
                              encode_channel(film.at(x, y)[c], e))
                        << x << " " << y << " " << c;
    }
}

}  // namespace
}  // namespace raylane
