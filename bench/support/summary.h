// bench: a summary table printed after a benchmark program's runs (`--summary`): the medians of
// the repetitions and the ratios that docs/performance.md reports, so that one command gives its
// figures.
#pragma once

#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace raylane::bench {

/// Every run's real time (ms) and counters by benchmark name, e.g.
/// "BM_Frame_Packet/threads:2/real_time": one entry per repetition, and the "median" aggregates
/// for when only aggregates are reported (--benchmark_report_aggregates_only).
struct Measured {
    std::map<std::string, std::vector<double>> ms;
    std::map<std::string, std::map<std::string, std::vector<double>>> counters;
    std::map<std::string, double> median_aggregate_ms;
    std::map<std::string, std::map<std::string, double>> median_aggregate_counters;

    /// Median over the repetitions of the real time, or of a counter; none if not run.
    std::optional<double> median_ms(const std::string& name) const;
    std::optional<double> median_counter(const std::string& name, const std::string& counter) const;
    bool empty() const { return ms.empty() && median_aggregate_ms.empty(); }
};

/// Prints a program's table from its measurements.
using Summary = void (*)(const Measured&, std::ostream&);

/// Runs the benchmarks as BENCHMARK_MAIN does. With `--summary` (taken out of argv first) the
/// runs are shown on the console, in colour when stdout is a terminal, and then
/// summary(measured, std::cout) prints its table. --benchmark_color,
/// --benchmark_counters_tabular and the BENCHMARK_FORMAT variable do not apply then; a
/// --benchmark_format other than console is refused.
int run_benchmarks(int argc, char** argv, Summary summary);

/// a / b when both are there.
std::optional<double> divide(std::optional<double> a, std::optional<double> b);

/// A 95 % bootstrap interval of median(num) / median(den), the ratio of two benchmarks' median
/// real times, from their repetitions: 2,000 resamples of each set with a fixed seed (the same
/// run gives the same interval). None when either has fewer than 5 repetitions. It covers the
/// spread within one run only, not a slower machine on another day.
std::optional<std::pair<double, double>> median_ratio_interval(const Measured& m,
                                                               const std::string& num,
                                                               const std::string& den);

/// The largest of the values that are there.
std::optional<double> best_of(const std::vector<std::optional<double>>& values);

/// The value by a printf format ("%.1f ms"), or "—" when it is missing.
std::string figure_text(std::optional<double> value, const char* format);

/// "1.23x", or "—" when either figure is missing.
std::string ratio_text(std::optional<double> num, std::optional<double> den);

}  // namespace raylane::bench
