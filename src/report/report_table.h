// report: a sweep as text for the terminal: the table of its points, the log-log fits of its
// curves and the summary of the packet path's speed-up.
#pragma once

#include <cstdio>
#include <vector>

#include "report/report_speedups.h"
#include "report/report_sweep.h"

namespace raylane {

/// The metrics line and the table of the sweep's points, a row per point, with an error line
/// under a point whose paths traced different numbers of rays. False when a check failed: a NaN
/// or Inf value or sample, or those ray counts.
bool print_sweep_table(std::FILE* out, const std::vector<SweepPoint>& points,
                       const SweepParams& sweep, const Speedups& speedups);

/// The slope of each (knob, path) curve against time and against samples, with R².
void print_fits(std::FILE* out, const std::vector<SweepPoint>& points, const SweepParams& sweep);

/// Packet over scalar in a few lines: at equal samples, at equal RMSE, from the fits, and the
/// efficiency. For a sweep of both paths (Speedups::both).
void print_speedup_summary(std::FILE* out, const std::vector<SweepPoint>& points,
                           const Speedups& speedups);

}  // namespace raylane
