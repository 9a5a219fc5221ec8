// bench for io/: mesh loading time of the shipped models (load_obj.cpp, load_ply.cpp), file
// read included.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "io/load_obj.h"
#include "io/load_ply.h"
#include "support/summary.h"

namespace raylane {
namespace {

template <MeshData (*Load)(const std::string&)>
void run_load(benchmark::State& state, const std::string& path) {
    std::error_code error;
    const auto bytes = std::filesystem::file_size(path, error);
    if (error) {
        state.SkipWithError((path + " not present").c_str());
        return;
    }
    size_t triangles = 0;
    for (auto _ : state) {
        MeshData mesh = Load(path);
        triangles = mesh.tris.size();
        benchmark::DoNotOptimize(mesh.positions.data());
    }
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(bytes));
    state.counters["triangles/s"] =
        benchmark::Counter(static_cast<double>(triangles) * static_cast<double>(state.iterations()),
                           benchmark::Counter::kIsRate);
}

const std::string models = RAYLANE_SHARED_DIR "/models/";

void BM_LoadObj_Dragon(benchmark::State& state) {
    run_load<load_obj>(state, models + "dragon.obj");
}
void BM_LoadPly_Dragon(benchmark::State& state) {
    run_load<load_ply>(state, models + "dragon.ply");
}
void BM_LoadPly_Bunny(benchmark::State& state) { run_load<load_ply>(state, models + "bunny.ply"); }

BENCHMARK(BM_LoadObj_Dragon)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LoadPly_Dragon)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LoadPly_Bunny)->Unit(benchmark::kMillisecond);

/// `--summary`: load times (medians).
void print_summary(const bench::Measured& m, std::ostream& out) {
    struct Row {
        const char* name;
        const char* file;
    };
    const Row rows[3] = {{"BM_LoadObj_Dragon", "dragon.obj"},
                         {"BM_LoadPly_Dragon", "dragon.ply"},
                         {"BM_LoadPly_Bunny", "bunny.ply"}};
    out << "Median of the repetitions\n\n| file | load time |\n|---|---:|\n";
    for (const Row& row : rows)
        out << "| " << row.file << " | " << bench::figure_text(m.median_ms(row.name), "%.1f ms")
            << " |\n";
}

}  // namespace
}  // namespace raylane

int main(int argc, char** argv) {
    return raylane::bench::run_benchmarks(argc, argv, raylane::print_summary);
}
