// report: a sweep's plot: RMSE against render time on log-log axes, a series per (knob, path)
// with standard-error bars, and a dashed slope of -1/2 (drawn by plot_svg.h).
#pragma once

#include <vector>

#include "report/plot_svg.h"
#include "report/report_cache.h"
#include "report/report_sweep.h"

namespace raylane {

/// The plot of the sweep's points: a series per knob and path in that order (circles for the
/// packet path, squares for the scalar one; triangles and diamonds for the light and glossy
/// knobs), the median time against the mean RMSE; the slope -1/2 through the first series'
/// middle point.
LogLogPlot sweep_plot(const SweepLabel& label, const SweepParams& sweep, const Reference& ref,
                      const std::vector<SweepPoint>& points);

}  // namespace raylane
