// Tests of report/report_metrics.cpp: the error metrics, the log-log fits and the time at an
// error. The `raylane report` command: tests/app/report_cli_test.cpp.
#include "report/report_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace raylane {
namespace {

Film constant_film(int w, int h, vec3 value) {
    Film f = make_film(w, h);
    std::fill(f.pixels.begin(), f.pixels.end(), value);
    return f;
}

// ---------------------------------------------------------------------------------------------
// Metrics

TEST(ComputeError, MatchesTheDefinitionsOnConstantFilms) {
    const Film ref = constant_film(4, 3, vec3(0.25f, 0.5f, 1.0f));
    const Film img = constant_film(4, 3, vec3(0.5f, 0.5f, 0.5f));
    const ErrorMetrics m = compute_error(img, ref);
    // per channel differences 0.25, 0, -0.5; every pixel alike
    const double mse = (0.0625 + 0.0 + 0.25) / 3.0;
    EXPECT_NEAR(m.mse, mse, 1e-12);
    EXPECT_NEAR(m.rmse, std::sqrt(mse), 1e-12);
    const double rel =
        (0.0625 / (0.0625 + relmse_epsilon) + 0.0 + 0.25 / (1.0 + relmse_epsilon)) / 3;
    EXPECT_NEAR(m.relmse, rel, 1e-12);
    const double smape = (0.25 / (0.75 + smape_epsilon) + 0.0 + 0.5 / (1.5 + smape_epsilon)) / 3.0;
    EXPECT_NEAR(m.smape, smape, 1e-12);
    EXPECT_NEAR(m.mean, 0.5, 1e-12);
    EXPECT_NEAR(m.ref_mean, 1.75 / 3.0, 1e-12);
    EXPECT_EQ(m.nan_values + m.inf_values + m.bad_pixels, 0u);
}

TEST(ComputeError, AveragesOverPixelsAndChannelsAndTakesEpsilon) {
    Film ref = constant_film(2, 2, vec3(0.0f));
    Film img = ref;
    img.at(1, 0) = vec3(0.2f, 0.0f, 0.0f);  // one value of 12 differs
    const ErrorMetrics m = compute_error(img, ref, 1e-3);
    const double d2 = double(0.2f) * double(0.2f);
    EXPECT_NEAR(m.mse, d2 / 12.0, 1e-15);
    EXPECT_NEAR(m.relmse, d2 / 1e-3 / 12.0, 1e-12);  // black reference: divided by epsilon
    EXPECT_EQ(compute_error(ref, ref).rmse, 0.0);
}

TEST(ComputeError, CountsNonFiniteValuesInsteadOfSkippingThem) {
    const Film ref = constant_film(3, 1, vec3(0.5f));
    Film img = ref;
    img.at(0, 0).x = std::nanf("");
    img.at(2, 0) = vec3(INFINITY, -INFINITY, 0.5f);
    const ErrorMetrics m = compute_error(img, ref);
    EXPECT_EQ(m.nan_values, 1u);
    EXPECT_EQ(m.inf_values, 2u);
    EXPECT_EQ(m.bad_pixels, 2u);
    EXPECT_FALSE(std::isfinite(m.rmse));
    EXPECT_THROW(compute_error(make_film(2, 2), make_film(2, 3)), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Fits and interpolation

TEST(FitLogLog, RecoversAKnownPowerLaw) {
    std::vector<double> x, y;
    for (double t : {0.01, 0.03, 0.1, 0.4, 2.0}) {
        x.push_back(t);
        y.push_back(0.02 * std::pow(t, -0.5));
    }
    const LineFit f = fit_loglog(x, y);
    EXPECT_EQ(f.n, 5u);
    EXPECT_NEAR(f.b, -0.5, 1e-12);
    EXPECT_NEAR(f.a, std::log10(0.02), 1e-12);
    EXPECT_NEAR(f.r2, 1.0, 1e-12);
}

TEST(FitLogLog, ScatterLowersR2ButKeepsTheSlopeNearby) {
    std::vector<double> x, y;
    const double wobble[] = {1.1, 0.9, 1.05, 0.95, 1.1, 0.9};
    for (int i = 0; i < 6; ++i) {
        x.push_back(std::pow(2.0, i));
        y.push_back(std::pow(x.back(), -0.75) * wobble[i]);
    }
    const LineFit f = fit_loglog(x, y);
    EXPECT_NEAR(f.b, -0.75, 0.05);
    EXPECT_LT(f.r2, 1.0);
    EXPECT_GT(f.r2, 0.95);
}

TEST(FitLogLog, InvertsToTheTimeThatReachesAnError) {
    const std::vector<double> t{0.1, 1.0, 10.0}, e{0.2, 0.2 / std::sqrt(10.0), 0.02};
    const LineFit f = fit_loglog(t, e);
    EXPECT_NEAR(*x_at_fit(f, 0.02), 10.0, 1e-9);
    EXPECT_NEAR(*x_at_fit(f, 0.002), 1000.0, 1e-6);  // extrapolates along the line
    EXPECT_FALSE(x_at_fit(f, 0.0).has_value());
    EXPECT_FALSE(x_at_fit(LineFit{}, 0.1).has_value());  // slope 0
}

TEST(FitLogLog, SkipsUnusablePointsAndNeedsTwo) {
    const std::vector<double> x{1.0, 0.0, 10.0, NAN}, y{1.0, 5.0, 0.1, 1.0};
    const LineFit f = fit_loglog(x, y);
    EXPECT_EQ(f.n, 2u);
    EXPECT_NEAR(f.b, -1.0, 1e-12);
    const std::vector<double> one{2.0};
    EXPECT_TRUE(std::isnan(fit_loglog(one, one).b));
    const std::vector<double> same{2.0, 2.0};
    EXPECT_TRUE(std::isnan(fit_loglog(same, one).b));
}

TEST(TimeAtError, InterpolatesLinearlyInLogLog) {
    const std::vector<double> t{1.0, 2.0, 4.0}, e{1.0, 0.5, 0.25};  // e = 1/t
    EXPECT_NEAR(*time_at_error(t, e, std::sqrt(0.5)), std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(*time_at_error(t, e, 0.3), 1.0 / 0.3, 1e-12);
    EXPECT_NEAR(*time_at_error(t, e, 0.5), 2.0, 1e-12);
    EXPECT_FALSE(time_at_error(t, e, 2.0).has_value());
    EXPECT_FALSE(time_at_error(t, e, 0.2).has_value());
    EXPECT_FALSE(time_at_error(t, e, 0.0).has_value());
}

TEST(TimeAtError, SlackMatchesAPointWithinTheFactor) {
    const std::vector<double> t{1.0, 2.0, 4.0}, e{1.0, 0.5, 0.25};
    EXPECT_EQ(*time_at_error(t, e, 1.02, 0.05), 1.0);
    EXPECT_EQ(*time_at_error(t, e, 0.245, 0.05), 4.0);
    EXPECT_FALSE(time_at_error(t, e, 1.2, 0.05).has_value());
}

TEST(TimeAtError, SlackCoversAPointJustAboveALocalMaximum) {
    // 2 spp noisier than the 1-spp pixel centre: the peak at 2 s brackets nothing above it
    const std::vector<double> t{1.0, 2.0, 4.0}, e{0.5, 0.6, 0.3};
    EXPECT_FALSE(time_at_error(t, e, 0.6 * 1.001).has_value());
    EXPECT_EQ(*time_at_error(t, e, 0.6 * 1.001, 0.05), 2.0);
}

TEST(TimeAtError, MinSlopeSkipsFlatSegments) {
    // a noisy plateau between 2 s and 4 s: there the time at an error is ill-conditioned
    const std::vector<double> t{1.0, 2.0, 4.0, 8.0}, e{0.4, 0.2, 0.198, 0.1};
    const double flat = 2.0 * std::pow(2.0, std::log(0.199 / 0.2) / std::log(0.198 / 0.2));
    EXPECT_NEAR(*time_at_error(t, e, 0.199), flat, 1e-12);
    EXPECT_FALSE(time_at_error(t, e, 0.199, 0.0, 0.1).has_value());
    EXPECT_EQ(*time_at_error(t, e, 0.199, 0.01, 0.1), 2.0);  // the nearest points' earliest
    EXPECT_NEAR(*time_at_error(t, e, 0.15, 0.0, 0.1),
                4.0 * std::pow(2.0, std::log(0.15 / 0.198) / std::log(0.1 / 0.198)), 1e-12);
}

TEST(TimeAtError, TakesTheEarliestTimeOnANonMonotoneCurve) {
    // error flattens and rises again at the end (a bias floor plus noise)
    const std::vector<double> t{1.0, 2.0, 4.0, 8.0}, e{0.4, 0.1, 0.05, 0.08};
    EXPECT_NEAR(*time_at_error(t, e, 0.2), 2.0 * std::pow(0.5, std::log(0.5) / std::log(0.25)),
                1e-12);
    // 0.06 is bracketed by (2 s, 0.1)-(4 s, 0.05) and again by (4 s, 0.05)-(8 s, 0.08)
    EXPECT_NEAR(*time_at_error(t, e, 0.06), 2.0 * std::pow(2.0, std::log(0.6) / std::log(0.5)),
                1e-12);
    // 2 spp noisier than the 1-spp pixel centre: an error a hair below the first point is
    // bracketed only by the later segment (2 s, 0.6)-(4 s, 0.3), but is reached at about 1 s
    const std::vector<double> t2{1.0, 2.0, 4.0}, e2{0.5, 0.6, 0.3};
    EXPECT_GT(*time_at_error(t2, e2, 0.5 * (1.0 - 1e-9)), 2.0);
    EXPECT_EQ(*time_at_error(t2, e2, 0.5 * (1.0 - 1e-9), 0.05), 1.0);
}

}  // namespace
}  // namespace raylane
