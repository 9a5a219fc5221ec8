// image: the 8-bit encoding of a linear channel (film.h encode_channel): clamped, sRGB or
// linear, rounded; NaN and infinities never reach the byte cast (numerics.md section 18).
#include "image/film.h"

#include <gtest/gtest.h>

#include <cmath>
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

}  // namespace
}  // namespace raylane
