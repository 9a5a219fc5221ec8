// report: a sweep as CSV, a row per point: the table's numbers plus the ray counts by type, the
// spread of the times, MSE - Var(ref) and the reference (error-vs-time.md, "What it does").
#pragma once

#include <string>
#include <vector>

#include "report/report_cache.h"
#include "report/report_speedups.h"
#include "report/report_sweep.h"

namespace raylane {

/// The CSV text: a header line, then a row per point in the order of `points`. The scene's name
/// is quoted (RFC 4180: a quote doubled); speedup_over_scalar is empty but on packet points of a
/// sweep of both paths that have one.
std::string sweep_csv(const SweepLabel& label, const SweepParams& sweep, const Reference& ref,
                      const std::vector<SweepPoint>& points, const Speedups& speedups);

}  // namespace raylane
