// Tests of report/compare.cpp's image differences: absolute, relative, RMSE, PSNR, 8-bit count.
#include "report/compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace raylane {
namespace {

Film film_of(std::initializer_list<vec3> pixels) {
    Film f = make_film(static_cast<int>(pixels.size()), 1);
    size_t i = 0;
    for (const vec3& p : pixels) f.pixels[i++] = p;
    return f;
}

TEST(DiffImages, MeasuresAbsoluteAndRelativeDifferences) {
    const Film a = film_of({vec3(0.5f, 0.0f, 0.0f), vec3(200.0f, 0.0f, 0.0f)});
    const Film b = film_of({vec3(0.5f, 0.0f, 0.0f), vec3(200.0f, 0.0f, 0.01f)});
    ImageDiff d = diff_images(a, b);
    EXPECT_DOUBLE_EQ(d.max_abs, double(0.01f));
    EXPECT_DOUBLE_EQ(d.max_rel, double(0.01f));  // below 1 the relative difference is absolute
    EXPECT_EQ(d.pixels_over_8bit, 1u);

    // one ulp of a bright pixel is a large absolute but a tiny relative difference
    const Film c =
        film_of({vec3(0.5f, 0.0f, 0.0f), vec3(std::nextafter(200.0f, 300.0f), 0.f, 0.f)});
    d = diff_images(a, c);
    EXPECT_GT(d.max_abs, 1e-5);
    EXPECT_LT(d.max_rel, 1e-7);
    EXPECT_EQ(d.pixels_over_8bit, 0u);
    EXPECT_NEAR(d.rmse, std::sqrt(d.max_abs * d.max_abs / 6.0), 1e-12);
}

TEST(DiffImages, NonFiniteDifferencesAreInfinite) {
    const Film a = film_of({vec3(0.5f)});
    const Film b = film_of({vec3(std::numeric_limits<float>::quiet_NaN())});
    const ImageDiff d = diff_images(a, b);
    EXPECT_TRUE(std::isinf(d.max_abs));
    EXPECT_TRUE(std::isinf(d.max_rel));
    EXPECT_THROW(diff_images(a, make_film(2, 1)), std::invalid_argument);
}

}  // namespace
}  // namespace raylane
