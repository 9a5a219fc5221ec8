// bench: the cost of rendering one frame over MPI ranks (`mpirun -n R raylane render`) against
// one process with the same cores, from the render times `raylane render` prints; `--summary`
// gives the ratios and the share of a frame the hand-out and gathering took.
//
//   build/release/bench/bench_distribute --summary --benchmark_repetitions=3
//
// Each benchmark runs the raylane binary once per iteration and reports the frame's render time
// (after load and BVH build, which every rank does alike) as its manual time.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include "support/summary.h"

namespace raylane {
namespace {

struct BenchScene {
    const char* name;
    const char* args;  ///< the scene and its size
};

const BenchScene scenes[] = {
    {"glass_bunny", "scenes/fig10_glass_bunny.json --width 320 --spp 16"},
    {"dragon", "scenes/dragon.json --spp 4"},
};

/// What a run printed: the render time (ms) and, under MPI, the serving and waiting times.
struct Printed {
    double render_ms = 0, serving_ms = 0, waiting_ms = 0;
    bool ok = false;
};

Printed run_raylane(const std::string& launcher, const BenchScene& scene, int threads) {
    const std::string out =
        (std::filesystem::temp_directory_path() / "raylane_bench_distribute.png").string();
    // not -q, which leaves out the lines read below; stderr goes into the pipe as well, so that it
    // is not a terminal and no progress line is drawn
    const std::string cmd = launcher + RAYLANE_BINARY + " render " + RAYLANE_SOURCE_DIR "/" +
                            scene.args + " --threads " + std::to_string(threads) + " -o " + out +
                            " 2>&1";
    Printed p;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return p;
    char line[512];
    while (std::fgets(line, sizeof line, pipe)) {
        double load = 0, build = 0;
        if (std::sscanf(line, "time       load %lf ms, build %lf ms, render %lf ms", &load, &build,
                        &p.render_ms) == 3)
            p.ok = true;
        int ranks = 0;
        long long units = 0;
        size_t all = 0;
        std::sscanf(line,
                    "ranks      %d; rank 0 rendered %lld of %zu units, spent %lf ms handing out "
                    "and gathering, %lf ms waiting",
                    &ranks, &units, &all, &p.serving_ms, &p.waiting_ms);
    }
    p.ok = pclose(pipe) == 0 && p.ok;
    std::filesystem::remove(out);
    return p;
}

std::string mpirun(int ranks) {
    return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " RAYLANE_MPIEXEC
           " -q --oversubscribe -n " +
           std::to_string(ranks) + " ";
}

/// One process, all the threads.
void BM_OneProcess(benchmark::State& state, const BenchScene* scene) {
    const int threads = static_cast<int>(state.range(0));
    for (auto _ : state) {
        const Printed p = run_raylane("", *scene, threads);
        if (!p.ok) {
            state.SkipWithError("raylane render failed (is the model on RAYLANE_MODEL_PATH?)");
            return;
        }
        state.SetIterationTime(p.render_ms / 1000.0);
    }
}

/// R ranks of T threads (range 0, 1).
void BM_Ranks(benchmark::State& state, const BenchScene* scene) {
    const int ranks = static_cast<int>(state.range(0)), threads = static_cast<int>(state.range(1));
    double serving = 0, frame = 0;
    for (auto _ : state) {
        const Printed p = run_raylane(mpirun(ranks), *scene, threads);
        if (!p.ok) {
            state.SkipWithError("mpirun raylane render failed");
            return;
        }
        state.SetIterationTime(p.render_ms / 1000.0);
        serving += p.serving_ms, frame += p.render_ms;
    }
    state.counters["serving_pct"] = frame > 0 ? 100.0 * serving / frame : 0.0;
}

void register_all() {
    for (const BenchScene& s : scenes) {
        benchmark::RegisterBenchmark((std::string("BM_OneProcess/") + s.name).c_str(),
                                     BM_OneProcess, &s)
            ->Arg(2)
            ->ArgName("threads")
            ->Iterations(1)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark((std::string("BM_Ranks/") + s.name).c_str(), BM_Ranks, &s)
            ->Args({2, 1})
            ->ArgNames({"ranks", "threads"})
            ->Iterations(1)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
    }
}

/// `--summary`: 2 ranks x 1 thread against 1 process x 2 threads, and the share of rank 0's
/// time spent handing out and gathering.
void print_summary(const bench::Measured& m, std::ostream& out) {
    out << "\n| scene | 1 process x 2 threads | 2 ranks x 1 thread | speed, ranks / process | "
           "hand-out and gathering |\n|---|---|---|---|---|\n";
    for (const BenchScene& s : scenes) {
        const std::string one =
            std::string("BM_OneProcess/") + s.name + "/threads:2/iterations:1/manual_time";
        const std::string two =
            std::string("BM_Ranks/") + s.name + "/ranks:2/threads:1/iterations:1/manual_time";
        const std::optional<double> a = m.median_ms(one), b = m.median_ms(two);
        out << "| " << s.name << " | " << bench::figure_text(a, "%.1f ms") << " | "
            << bench::figure_text(b, "%.1f ms") << " | " << bench::ratio_text(a, b) << " | "
            << bench::figure_text(m.median_counter(two, "serving_pct"), "%.2f %%") << " |\n";
    }
}

}  // namespace
}  // namespace raylane

int main(int argc, char** argv) {
    raylane::register_all();
    return raylane::bench::run_benchmarks(argc, argv, raylane::print_summary);
}
