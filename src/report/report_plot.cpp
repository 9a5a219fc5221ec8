// report: a sweep's plot (report_plot.h).
#include "report/report_plot.h"

#include <string>
#include <utility>

namespace raylane {

LogLogPlot sweep_plot(const SweepLabel& label, const SweepParams& sweep, const Reference& ref,
                      const std::vector<SweepPoint>& points) {
    LogLogPlot plot;
    plot.title = label.scene + ": RMSE against render time (" + std::to_string(label.width) + "x" +
                 std::to_string(label.height) + ", " + std::to_string(label.threads) + " threads)";
    plot.x_label = "render time [s], median of " + std::to_string(sweep.repeats);
    plot.y_label = ref.spp > 0 ? "RMSE against " + std::to_string(ref.spp) + " spp reference"
                               : "RMSE against the analytic reference";
    for (SweepKnob k : sweep.knobs) {
        for (RenderPath p : sweep.paths) {
            PlotSeries s;
            s.label = std::string(path_name(p)) +
                      (k == SweepKnob::spp ? "" : std::string(", ") + knob_name(k) + " samples");
            s.marker = p == RenderPath::packet ? PlotMarker::circle : PlotMarker::square;
            if (k != SweepKnob::spp)
                s.marker = k == SweepKnob::light ? PlotMarker::triangle : PlotMarker::diamond;
            for (const SweepPoint& pt : points) {
                if (pt.path != p || pt.knob != k) continue;
                s.x.push_back(pt.seconds_median);
                s.y.push_back(pt.error.rmse);
                s.y_err.push_back(pt.rmse_se);
            }
            plot.series.push_back(std::move(s));
        }
    }
    if (!plot.series.empty() && !plot.series[0].x.empty()) {
        const size_t mid = plot.series[0].x.size() / 2;
        plot.reference =
            ReferenceSlope{-0.5, plot.series[0].x[mid], plot.series[0].y[mid], "slope -1/2"};
    }
    return plot;
}

}  // namespace raylane
