// Tests of report/report_speedups.cpp: the speed-up at equal RMSE, the ratios at equal samples
// and their spread, on made-up sweeps.
#include "report/report_speedups.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "support/sweep_points.h"

namespace raylane {
namespace {

using test::made_up_params;
using test::made_up_sweep;

TEST(Speedups, PacketTwiceAsFastAtTheSameErrorIsTwiceAsFastEverywhere) {
    const SweepParams sweep = made_up_params({SweepKnob::spp, SweepKnob::light});
    const std::vector<SweepPoint> points = made_up_sweep(sweep);
    const Speedups s = speedups_of(points, sweep);
    ASSERT_TRUE(s.both);
    EXPECT_EQ(s.at_equal_rmse.size(), 6u);  // (knob, samples) of every packet point
    ASSERT_EQ(s.speedups.size(), 6u);
    ASSERT_EQ(s.time_ratios.size(), 6u);
    ASSERT_EQ(s.efficiency_ratios.size(), 6u);
    for (size_t i = 0; i < 6; ++i) {
        EXPECT_NEAR(s.speedups[i], 2.0, 1e-12);
        EXPECT_NEAR(s.time_ratios[i], 2.0, 1e-12);
        EXPECT_NEAR(s.efficiency_ratios[i], 2.0, 1e-12);
    }
    for (const SweepPoint& pt : points) {
        ASSERT_TRUE(s.of(pt).has_value());  // looked up by (knob, samples), whatever the path
        EXPECT_NEAR(*s.of(pt), 2.0, 1e-12);
    }
}

TEST(Speedups, NoneWithOnePath) {
    SweepParams sweep = made_up_params();
    sweep.paths = {RenderPath::packet};
    const std::vector<SweepPoint> points = made_up_sweep(sweep);
    const Speedups s = speedups_of(points, sweep);
    EXPECT_FALSE(s.both);
    EXPECT_TRUE(s.at_equal_rmse.empty());
    EXPECT_TRUE(s.speedups.empty());
    EXPECT_FALSE(s.of(points[0]).has_value());
}

TEST(Speedups, NoSpeedUpWhereTheRmseIsOutsideTheScalarCurve) {
    const SweepParams sweep = made_up_params();
    std::vector<SweepPoint> points = made_up_sweep(sweep);
    points[0].error.rmse = 1.0;  // packet at 1 sample: above every scalar RMSE
    const Speedups s = speedups_of(points, sweep);
    EXPECT_FALSE(s.of(points[0]).has_value());
    EXPECT_EQ(s.speedups.size(), 2u);
    EXPECT_EQ(s.time_ratios.size(), 3u);  // at equal samples, whatever the error
}

TEST(Spread, MedianAndRangeOfTheFiniteValues) {
    const double inf = std::numeric_limits<double>::infinity();
    const Spread s = spread_of({3.0, std::nan(""), 1.0, inf, 2.0, 10.0});
    EXPECT_EQ(s.n, 4u);
    EXPECT_EQ(s.median, 2.5);
    EXPECT_EQ(s.lo, 1.0);
    EXPECT_EQ(s.hi, 10.0);
    EXPECT_EQ(spread_of({5.0, 1.0, 3.0}).median, 3.0);
    const Spread none = spread_of({std::nan("")});
    EXPECT_EQ(none.n, 0u);
    EXPECT_EQ(none.median, 0.0);
}

}  // namespace
}  // namespace raylane
