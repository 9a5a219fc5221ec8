// bench: the `--summary` reporter (summary.h).
#include "summary.h"

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <random>
#include <sstream>

namespace raylane::bench {

namespace {

std::optional<double> median(std::vector<double> v) {
    if (v.empty()) return std::nullopt;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Debian's libbenchmark is built without NDEBUG, so every run's header says "***WARNING***
/// Library was built as DEBUG. Timings may be affected."; this says what it means, on stderr
/// (stdout may be a JSON or CSV report).
void print_debug_library_note() {
    std::fprintf(stderr,
                 "(A \"Library was built as DEBUG\" warning in the header below is about Debian's "
                 "Google Benchmark package, whose own code keeps its assertions; the code "
                 "measured is Raylane's, built -O3 -DNDEBUG.)\n");
}

/// What --help adds to Google Benchmark's own usage.
void print_summary_usage(const char* program) {
    std::printf(
        "%s: a Google Benchmark program of Raylane (docs/performance.md).\n"
        "  --summary   after the runs, print a Markdown table of the medians of the repetitions,\n"
        "              and the ratios (to the scalar path, to Embree)\n"
        "              (use --benchmark_repetitions=3 or more); console output only\n"
        "Google Benchmark's own options:\n",
        program);
}

/// The console reporter, keeping every run's figures for the summary.
class SummaryReporter : public benchmark::ConsoleReporter {
  public:
    explicit SummaryReporter(Measured& measured)
        : ConsoleReporter(isatty(fileno(stdout)) ? OO_Color : OO_None), measured_(measured) {}

    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& run : runs) {
            if (run.error_occurred) continue;
            const bool repetition = run.run_type == Run::RT_Iteration;
            if (!repetition && run.aggregate_name != "median") continue;
            const std::string base = run.run_name.str();  // without "_median"
            // real time in ms, whatever unit the benchmark reports in
            const double ms = run.GetAdjustedRealTime() *
                              benchmark::GetTimeUnitMultiplier(benchmark::kMillisecond) /
                              benchmark::GetTimeUnitMultiplier(run.time_unit);
            if (repetition) {
                measured_.ms[base].push_back(ms);
                for (const auto& [key, counter] : run.counters)
                    measured_.counters[base][key].push_back(counter.value);
            } else {  // "NAME_median"
                measured_.median_aggregate_ms[base] = ms;
                for (const auto& [key, counter] : run.counters)
                    measured_.median_aggregate_counters[base][key] = counter.value;
            }
        }
        ConsoleReporter::ReportRuns(runs);
    }

  private:
    Measured& measured_;
};

}  // namespace

std::optional<double> Measured::median_ms(const std::string& name) const {
    if (const auto it = ms.find(name); it != ms.end()) return median(it->second);
    if (const auto it = median_aggregate_ms.find(name); it != median_aggregate_ms.end())
        return it->second;
    return std::nullopt;
}

std::optional<double> Measured::median_counter(const std::string& name,
                                               const std::string& counter) const {
    if (const auto it = counters.find(name); it != counters.end()) {
        const auto c = it->second.find(counter);
        return c == it->second.end() ? std::nullopt : median(c->second);
    }
    if (const auto it = median_aggregate_counters.find(name);
        it != median_aggregate_counters.end()) {
        const auto c = it->second.find(counter);
        if (c != it->second.end()) return c->second;
    }
    return std::nullopt;
}

int run_benchmarks(int argc, char** argv, Summary summary) {
    if (argc < 1) return 2;
    bool want_summary = false, other_format = false;
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--help") == 0) print_summary_usage(argv[0]);
        if (std::strcmp(argv[i], "--summary") == 0) {
            want_summary = true;
            continue;
        }
        if (std::strncmp(argv[i], "--benchmark_format=", 19) == 0)
            other_format = std::strcmp(argv[i] + 19, "console") != 0;
        argv[kept++] = argv[i];
    }
    argc = kept;
    argv[argc] = nullptr;
    if (want_summary && other_format) {
        std::fprintf(stderr,
                     "%s: --summary prints to the console; it does not combine with "
                     "--benchmark_format (use --benchmark_out for a file)\n",
                     argv[0]);
        return 2;
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    print_debug_library_note();
    if (want_summary) {
        Measured measured;
        SummaryReporter reporter(measured);
        benchmark::RunSpecifiedBenchmarks(&reporter);
        if (!measured.empty()) {  // not for --benchmark_list_tests
            std::ostringstream table;
            summary(measured, table);
            std::cout << '\n' << table.str();
            if (table.str().find("—") != std::string::npos)
                std::cout << "\n— marks a figure whose benchmark did not run: left out by "
                             "--benchmark_filter, or a contender this build lacks (Embree, when "
                             "libembree-dev is not installed).\n";
        }
    } else {
        benchmark::RunSpecifiedBenchmarks();
    }
    benchmark::Shutdown();
    return 0;
}

std::optional<double> divide(std::optional<double> a, std::optional<double> b) {
    if (!a || !b || *b == 0.0) return std::nullopt;
    return *a / *b;
}

std::optional<std::pair<double, double>> median_ratio_interval(const Measured& m,
                                                               const std::string& num,
                                                               const std::string& den) {
    const auto a = m.ms.find(num), b = m.ms.find(den);
    constexpr size_t min_repetitions = 5;
    if (a == m.ms.end() || b == m.ms.end() || a->second.size() < min_repetitions ||
        b->second.size() < min_repetitions)
        return std::nullopt;
    std::mt19937 rng(20261203);
    auto resampled_median = [&](const std::vector<double>& v) {
        std::uniform_int_distribution<size_t> pick(0, v.size() - 1);
        std::vector<double> r(v.size());
        for (double& x : r) x = v[pick(rng)];
        return *median(std::move(r));
    };
    constexpr size_t resamples = 2000;
    std::vector<double> ratios(resamples);
    for (double& r : ratios) r = resampled_median(a->second) / resampled_median(b->second);
    std::sort(ratios.begin(), ratios.end());
    return std::make_pair(ratios[resamples / 40], ratios[resamples - 1 - resamples / 40]);
}

std::optional<double> best_of(const std::vector<std::optional<double>>& values) {
    std::optional<double> best;
    for (const auto& v : values)
        if (v && (!best || *v > *best)) best = v;
    return best;
}

std::string figure_text(std::optional<double> value, const char* format) {
    if (!value) return "—";
    char text[64];
    std::snprintf(text, sizeof text, format, *value);
    return text;
}

std::string ratio_text(std::optional<double> num, std::optional<double> den) {
    return figure_text(divide(num, den), "%.2fx");
}

}  // namespace raylane::bench
