// bench: a summary table printed after a benchmark program's runs (`--summary`): the medians of
// the repetitions and the ratios that docs/performance.md reports, so that one command gives the
// figures and the targets they are held to.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace raylane::bench {

/// Every run's real time (ms) and counters, by benchmark name ("BM_Frame_Packet/threads:2/
/// real_time"), one entry per repetition; aggregates (mean, median, ...) are left out.
struct Measured {
    std::map<std::string, std::vector<double>> ms;
    std::map<std::string, std::map<std::string, std::vector<double>>> counters;

    /// Median over the repetitions of the real time, or of a counter; none if not run.
    std::optional<double> median_ms(const std::string& name) const;
    std::optional<double> median_counter(const std::string& name, const std::string& counter) const;
};

using Summary = std::function<void(const Measured&, std::ostream&)>;

/// Runs the benchmarks as BENCHMARK_MAIN does. With `--summary` (taken out of argv first) the
/// runs are shown on the console as usual (`--benchmark_format` does not apply) and then
/// summary(measured, std::cout) prints its table.
int run_benchmarks(int argc, char** argv, const Summary& summary);

/// "1.23x", or "—" when either figure is missing.
std::string ratio_text(std::optional<double> num, std::optional<double> den);

/// "met" when ratio >= target, "not met" when below, "—" when the ratio is missing.
std::string verdict(std::optional<double> ratio, double target);

/// a / b when both are there.
std::optional<double> divide(std::optional<double> a, std::optional<double> b);

/// The largest of the values that are there.
std::optional<double> best_of(const std::vector<std::optional<double>>& values);

}  // namespace raylane::bench
