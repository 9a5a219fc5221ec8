// Tests of report/report_plot.cpp: a series per knob and path with its markers, the points in
// time and RMSE, the slope through the first series' middle point, the labels.
#include "report/report_plot.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/sweep_points.h"

namespace raylane {
namespace {

using test::made_up_params;
using test::made_up_sweep;

TEST(SweepPlot, ASeriesPerKnobAndPathInThatOrder) {
    const SweepParams sweep = made_up_params({SweepKnob::spp, SweepKnob::light, SweepKnob::glossy});
    const std::vector<SweepPoint> points = made_up_sweep(sweep);
    Reference ref;
    ref.spp = 400;
    const LogLogPlot plot = sweep_plot(SweepLabel{"bunny", 32, 24, 2}, sweep, ref, points);
    ASSERT_EQ(plot.series.size(), 6u);
    const std::vector<std::string> labels{"packet",
                                          "scalar",
                                          "packet, light samples",
                                          "scalar, light samples",
                                          "packet, glossy samples",
                                          "scalar, glossy samples"};
    const std::vector<PlotMarker> markers{PlotMarker::circle,   PlotMarker::square,
                                          PlotMarker::triangle, PlotMarker::triangle,
                                          PlotMarker::diamond,  PlotMarker::diamond};
    for (size_t i = 0; i < plot.series.size(); ++i) {
        const PlotSeries& s = plot.series[i];
        EXPECT_EQ(s.label, labels[i]);
        EXPECT_EQ(s.marker, markers[i]) << s.label;
        ASSERT_EQ(s.x.size(), 3u) << s.label;
        ASSERT_EQ(s.y_err.size(), 3u) << s.label;
        for (size_t j = 0; j < 3; ++j) {
            const SweepPoint& pt = points[i * 3 + j];  // run_sweep's order: knob, path, samples
            EXPECT_EQ(s.x[j], pt.seconds_median);
            EXPECT_EQ(s.y[j], pt.error.rmse);
            EXPECT_EQ(s.y_err[j], pt.rmse_se);
        }
    }
    ASSERT_TRUE(plot.reference.has_value());
    EXPECT_EQ(plot.reference->slope, -0.5);
    EXPECT_EQ(plot.reference->x0, plot.series[0].x[1]);
    EXPECT_EQ(plot.reference->y0, plot.series[0].y[1]);
    EXPECT_EQ(plot.title, "bunny: RMSE against render time (32x24, 2 threads)");
    EXPECT_EQ(plot.x_label, "render time [s], median of 2");
    EXPECT_EQ(plot.y_label, "RMSE against 400 spp reference");
}

TEST(SweepPlot, AnAnalyticReferenceAndNoPoints) {
    const SweepParams sweep = made_up_params();
    const LogLogPlot plot = sweep_plot(SweepLabel{"sphere", 8, 8, 1}, sweep, Reference{}, {});
    EXPECT_EQ(plot.y_label, "RMSE against the analytic reference");
    EXPECT_EQ(plot.series.size(), 2u);  // a series per path, empty
    EXPECT_FALSE(plot.reference.has_value());
}

}  // namespace
}  // namespace raylane
