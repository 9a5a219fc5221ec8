// Tests of render/render_params: AOV names and the PNG mappings of raw AOV films.
#include "render/render_params.h"

#include <gtest/gtest.h>

#include <cmath>

namespace raylane {
namespace {

/// A film of one row holding `values` in every channel.
Film row_of(const std::vector<float>& values) {
    Film f = make_film(int(values.size()), 1);
    for (size_t i = 0; i < values.size(); ++i) f.pixels[i] = vec3(values[i]);
    return f;
}

TEST(RenderParams, AovNamesRoundTrip) {
    for (Aov a : {Aov::color, Aov::normal, Aov::depth, Aov::bvh_cost}) {
        Aov back = Aov::color;
        EXPECT_TRUE(parse_aov(aov_name(a), back));
        EXPECT_EQ(back, a);
    }
    Aov unused = Aov::color;
    EXPECT_FALSE(parse_aov("albedo", unused));
}

TEST(RenderParams, DepthIsALogScaleFromTheNearestHitToThe98thPercentile) {
    // 100 hits from 1 to 100, a miss, and one far outlier (a floor at the horizon)
    std::vector<float> v;
    for (int i = 1; i <= 100; ++i) v.push_back(float(i));
    v.push_back(0.0f);
    v.push_back(1e6f);
    const AovView view = visualise_aov(row_of(v), Aov::depth);
    const float far = 99.0f;                     // the 98th percentile of the 101 hit distances
    EXPECT_EQ(view.film.pixels[0], vec3(1.0f));  // nearest: white
    EXPECT_NEAR(view.film.pixels[9].x, std::log(far / 10.0f) / std::log(far), 1e-6f);
    EXPECT_EQ(view.film.pixels[98], vec3(0.0f));   // the percentile: black
    EXPECT_EQ(view.film.pixels[100], vec3(0.0f));  // the miss
    EXPECT_EQ(view.film.pixels[101], vec3(0.0f));  // beyond: black
    EXPECT_EQ(view.scale,
              "depth: log scale, white at 1, black at 99 and beyond (scene units along the ray); "
              "misses black");
}

TEST(RenderParams, DepthWithoutHitsIsBlackAndSaysSo) {
    const AovView view = visualise_aov(row_of({0.0f, 0.0f}), Aov::depth);
    EXPECT_EQ(view.film.pixels[0], vec3(0.0f));
    EXPECT_EQ(view.scale, "depth: no ray hit anything; the image is black");
}

TEST(RenderParams, CostRunsFromDarkBlueAtZeroToWhiteAtTheLargestCount) {
    const AovView view = visualise_aov(row_of({0.0f, 50.0f, 200.0f}), Aov::bvh_cost);
    EXPECT_GT(view.film.pixels[0].z, view.film.pixels[0].x);  // blue
    EXPECT_EQ(view.film.pixels[2], vec3(1.0f));               // white
    EXPECT_EQ(view.scale,
              "bvh-cost: false colour from 0 (dark blue) through green and yellow to 200 nodes "
              "visited (white)");
}

TEST(RenderParams, NormalsMapToHalfPlusHalfAndColourPassesThrough) {
    Film f = row_of({-1.0f, 1.0f});
    const AovView n = visualise_aov(f, Aov::normal);
    EXPECT_EQ(n.film.pixels[0], vec3(0.0f));
    EXPECT_EQ(n.film.pixels[1], vec3(1.0f));
    const AovView c = visualise_aov(f, Aov::color);
    EXPECT_EQ(c.film.pixels, f.pixels);
    EXPECT_TRUE(c.scale.empty());
}

}  // namespace
}  // namespace raylane
