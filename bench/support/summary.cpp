// bench: the `--summary` reporter (summary.h).
#include "summary.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <iostream>

namespace raylane::bench {

namespace {

std::optional<double> median(std::vector<double> v) {
    if (v.empty()) return std::nullopt;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// The console reporter, keeping every run's figures for the summary.
class SummaryReporter : public benchmark::ConsoleReporter {
  public:
    explicit SummaryReporter(Measured& measured) : measured_(measured) {}

    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& run : runs) {
            if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
            const std::string name = run.benchmark_name();
            // real time in ms, whatever unit the benchmark reports in
            const double to_ms = benchmark::GetTimeUnitMultiplier(benchmark::kMillisecond) /
                                 benchmark::GetTimeUnitMultiplier(run.time_unit);
            measured_.ms[name].push_back(run.GetAdjustedRealTime() * to_ms);
            for (const auto& [key, counter] : run.counters)
                measured_.counters[name][key].push_back(counter.value);
        }
        ConsoleReporter::ReportRuns(runs);
    }

  private:
    Measured& measured_;
};

}  // namespace

std::optional<double> Measured::median_ms(const std::string& name) const {
    const auto it = ms.find(name);
    return it == ms.end() ? std::nullopt : median(it->second);
}

std::optional<double> Measured::median_counter(const std::string& name,
                                               const std::string& counter) const {
    const auto it = counters.find(name);
    if (it == counters.end()) return std::nullopt;
    const auto c = it->second.find(counter);
    return c == it->second.end() ? std::nullopt : median(c->second);
}

int run_benchmarks(int argc, char** argv, const Summary& summary) {
    bool want_summary = false;
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--summary") == 0)
            want_summary = true;
        else
            argv[kept++] = argv[i];
    }
    argc = kept;
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    if (want_summary) {
        Measured measured;
        SummaryReporter reporter(measured);
        benchmark::RunSpecifiedBenchmarks(&reporter);
        std::cout << '\n';
        summary(measured, std::cout);
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

std::optional<double> best_of(const std::vector<std::optional<double>>& values) {
    std::optional<double> best;
    for (const auto& v : values)
        if (v && (!best || *v > *best)) best = v;
    return best;
}

std::string ratio_text(std::optional<double> num, std::optional<double> den) {
    const std::optional<double> r = divide(num, den);
    if (!r) return "—";
    char text[32];
    std::snprintf(text, sizeof text, "%.2fx", *r);
    return text;
}

std::string verdict(std::optional<double> ratio, double target) {
    if (!ratio) return "—";
    return *ratio >= target ? "met" : "not met";
}

}  // namespace raylane::bench
