// Benchmarks of accel/build_median.cpp: the median-split BVH of the bunny, the dragon, and the
// dragon subdivided to 400k and 1.6M triangles (how build time grows with n). The build's vector
// loops run on the instruction set in use (support/isa_sets.h: RAYLANE_ISA, else the widest this
// CPU runs); every set builds the same tree.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "accel/bvh.h"
#include "io/load_mesh.h"
#include "support/isa_sets.h"
#include "support/summary.h"

namespace raylane {
namespace {

/// Splits every triangle into four at its edge midpoints (positions only).
MeshData subdivide(const MeshData& in) {
    MeshData out;
    out.positions = in.positions;
    out.tris.reserve(in.tris.size() * 4);
    for (const uvec3& t : in.tris) {
        const uint32_t base = static_cast<uint32_t>(out.positions.size());
        const vec3 a = in.positions[t.x], b = in.positions[t.y], c = in.positions[t.z];
        out.positions.push_back(0.5f * (a + b));
        out.positions.push_back(0.5f * (b + c));
        out.positions.push_back(0.5f * (c + a));
        const uint32_t ab = base, bc = base + 1, ca = base + 2;
        out.tris.push_back({t.x, ab, ca});
        out.tris.push_back({ab, t.y, bc});
        out.tris.push_back({ca, bc, t.z});
        out.tris.push_back({ab, bc, ca});
    }
    return out;
}

/// Loaded once per process; level = number of subdivisions.
const MeshData* model(const std::string& file, int level) {
    static std::map<std::pair<std::string, int>, MeshData> cache;
    auto key = std::make_pair(file, level);
    if (auto it = cache.find(key); it != cache.end()) return &it->second;
    const std::string path = std::string(RAYLANE_SHARED_DIR) + "/models/" + file;
    if (!std::filesystem::exists(path)) return nullptr;
    MeshData m = level == 0 ? load_mesh(path) : subdivide(*model(file, level - 1));
    return &cache.emplace(key, std::move(m)).first->second;
}

/// The median-split build's phases, as the counters name them, in the order they run.
std::vector<std::pair<std::string, double>> phase_times(const BuildPhases& p) {
    return {{"centroids_ms", p.centroids}, {"sorts_ms", p.sorts}, {"splits_ms", p.splits},
            {"vertices_ms", p.vertices},   {"boxes_ms", p.boxes}, {"collapse_ms", p.collapse}};
}

/// Builds the mesh in the timed loop. With `warm_up`, one untimed build first: every timed build
/// then follows a build of the same mesh, as a repeated build does. (Without it, a repetition of
/// one iteration would time one build after other benchmarks ran: Google Benchmark fixes the
/// iteration count of every repetition from the first repetition's first build, which is the
/// process's first build of that size, and for the 1.6M dragon that cold build took 0.31 s,
/// longer than --benchmark_min_time=0.3: one iteration per repetition.)
void build_mesh(benchmark::State& state, const char* file, int level, BvhBuild method,
                bool warm_up) {
    const MeshData* mesh = model(file, level);
    if (!mesh) {
        state.SkipWithError("model not found");
        return;
    }
    if (warm_up) {  // freed before the timed builds, as a repeated build's predecessor is
        const MeshAccel warm = build_mesh_accel(*mesh, BuildParams{.method = method});
        benchmark::DoNotOptimize(warm.bvh.nodes.data());
    }
    BuildPhases sum;
    for (auto _ : state) {
        MeshAccel accel = build_mesh_accel(*mesh, BuildParams{.method = method});
        benchmark::DoNotOptimize(accel.bvh.nodes.data());
        sum += accel.phases;
    }
    if (method == BvhBuild::median) {  // each phase's mean time per build
        for (const auto& [name, ms] : phase_times(sum))
            state.counters[name] = benchmark::Counter(ms, benchmark::Counter::kAvgIterations);
    }
    const double n = static_cast<double>(mesh->tris.size());
    state.counters["triangles"] = n;
    state.counters["triangles/s"] =
        benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
    state.SetComplexityN(static_cast<int64_t>(n));
}

void BM_BuildMedian(benchmark::State& state, const char* file, int level) {
    build_mesh(state, file, level, BvhBuild::median, true);
}

/// The binned SAH build (a comparison option), the same way.
void BM_BuildSah(benchmark::State& state, const char* file, int level) {
    build_mesh(state, file, level, BvhBuild::sah, true);
}

/// The first build of the process, once: what `raylane render` and `raylane info` pay, every
/// page of the build's memory fresh from the kernel. (BM_BuildMedian repeats the build, and
/// then glibc serves the smaller sizes' arrays from memory the previous iteration freed, while
/// arrays above its 32 MiB mmap threshold are mapped afresh each time: the sizes are not
/// measured alike.) One process per measurement:
///   for s in 100k 400k 1600k; do for r in 1 2 3 4 5; do
///     bench_build --benchmark_filter="BM_BuildMedianFirst/dragon_$s"; done; done
void BM_BuildMedianFirst(benchmark::State& state, const char* file, int level) {
    build_mesh(state, file, level, BvhBuild::median, false);  // registered with Iterations(1)
}

/// The median-split build with subtrees of at most state.range(0) primitives
/// (BuildParams::median_subtree; the default is 2^17): how the limit moves the build time of
/// the larger meshes. The tree is the same for every limit.
void BM_BuildMedianSubtree(benchmark::State& state, const char* file, int level) {
    const MeshData* mesh = model(file, level);
    if (!mesh) {
        state.SkipWithError("model not found");
        return;
    }
    const BuildParams params{.median_subtree = static_cast<uint32_t>(state.range(0))};
    {
        MeshAccel warm = build_mesh_accel(*mesh, params);  // untimed, as in build_mesh
        benchmark::DoNotOptimize(warm.bvh.nodes.data());
    }
    for (auto _ : state) {
        MeshAccel accel = build_mesh_accel(*mesh, params);
        benchmark::DoNotOptimize(accel.bvh.nodes.data());
    }
    state.counters["triangles/s"] = benchmark::Counter(
        static_cast<double>(mesh->tris.size()), benchmark::Counter::kIsIterationInvariantRate);
}

/// build_bvh_median alone, on triangle boxes made once (the rest of BM_BuildMedian is the
/// mesh's part: the boxes, and the vertices in leaf order).
void BM_BuildBvhMedian(benchmark::State& state, const char* file, int level) {
    const MeshData* mesh = model(file, level);
    if (!mesh) {
        state.SkipWithError("model not found");
        return;
    }
    std::vector<Aabb> bounds(mesh->tris.size());
    for (size_t i = 0; i < mesh->tris.size(); ++i)
        for (uint32_t v : {mesh->tris[i].x, mesh->tris[i].y, mesh->tris[i].z})
            bounds[i].grow(mesh->positions[v]);
    for (auto _ : state) {
        Bvh bvh = build_bvh_median(bounds, BuildParams{});
        benchmark::DoNotOptimize(bvh.nodes.data());
    }
    state.counters["triangles/s"] = benchmark::Counter(
        static_cast<double>(bounds.size()), benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK_CAPTURE(BM_BuildMedian, bunny, "bunny.ply", 0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildMedian, dragon_100k, "dragon.ply", 0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildMedian, dragon_400k, "dragon.ply", 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildMedian, dragon_1600k, "dragon.ply", 2)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildSah, dragon_100k, "dragon.ply", 0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildMedianFirst, dragon_100k, "dragon.ply", 0)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildMedianFirst, dragon_400k, "dragon.ply", 1)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildMedianFirst, dragon_1600k, "dragon.ply", 2)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildMedianSubtree, dragon_400k, "dragon.ply", 1)
    ->RangeMultiplier(2)
    ->Range(1 << 16, 1 << 19)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildMedianSubtree, dragon_1600k, "dragon.ply", 2)
    ->RangeMultiplier(2)
    ->Range(1 << 16, 1 << 19)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildBvhMedian, dragon_100k, "dragon.ply", 0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildBvhMedian, dragon_1600k, "dragon.ply", 2)->Unit(benchmark::kMillisecond);

/// The repeated build's phases (medians over the repetitions of each phase's mean time per
/// build) at each size, and each phase's growth per 4x step beside what its order allows.
void print_phases(const bench::Measured& m, std::ostream& out) {
    const char* sizes[3] = {"dragon_100k", "dragon_400k", "dragon_1600k"};
    auto name = [&](int i) { return std::string("BM_BuildMedian/") + sizes[i]; };
    const std::vector<std::pair<std::string, double>> phases = phase_times(BuildPhases{});
    if (!m.median_counter(name(1), phases[0].first) && !m.median_counter(name(2), phases[0].first))
        return;  // no build of 400k or 1.6M triangles was run
    const char* labels[] = {"centroids (and the arrays made)",
                            "the three radix sorts",
                            "median splits",
                            "vertices in leaf order",
                            "node boxes",
                            "wide tree collapsed, leaves packed"};
    const char* orders[] = {"n", "n", "n log n", "n", "n", "n"};
    out << "\nWhere the repeated build's time goes (each phase's mean per build, median of the "
           "repetitions):\n\n| phase | grows as | 100k | 400k | 1.6M | 100k → 400k | 400k → 1.6M "
           "|\n|---|---|---:|---:|---:|---:|---:|\n";
    std::optional<double> n[3];
    for (int i = 0; i < 3; ++i) n[i] = m.median_counter(name(i), "triangles");
    std::optional<double> sum[3];
    auto add = [](std::optional<double>& a, std::optional<double> b) {
        if (b) a = a.value_or(0.0) + *b;
    };
    for (size_t p = 0; p < phases.size(); ++p) {
        std::optional<double> ms[3];
        for (int i = 0; i < 3; ++i) {
            ms[i] = m.median_counter(name(i), phases[p].first);
            add(sum[i], ms[i]);
        }
        out << "| " << labels[p] << " | " << orders[p];
        for (int i = 0; i < 3; ++i) out << " | " << bench::figure_text(ms[i], "%.2f ms");
        for (int i = 1; i < 3; ++i) out << " | " << bench::ratio_text(ms[i], ms[i - 1]);
        out << " |\n";
    }
    out << "| the phases' sum | | " << bench::figure_text(sum[0], "%.2f ms") << " | "
        << bench::figure_text(sum[1], "%.2f ms") << " | " << bench::figure_text(sum[2], "%.2f ms")
        << " | " << bench::ratio_text(sum[1], sum[0]) << " | " << bench::ratio_text(sum[2], sum[1])
        << " |\n";
    out << "| what the order allows | n: | | | | " << bench::ratio_text(n[1], n[0]) << " | "
        << bench::ratio_text(n[2], n[1]) << " |\n";
    auto nlogn = [&](int i) -> std::optional<double> {
        if (!n[i] || !n[i - 1]) return std::nullopt;
        return (*n[i] * std::log(*n[i])) / (*n[i - 1] * std::log(*n[i - 1]));
    };
    out << "| | n log n: | | | | " << bench::figure_text(nlogn(1), "%.2fx") << " | "
        << bench::figure_text(nlogn(2), "%.2fx") << " |\n";
    out << "\nThe sum leaves out freeing the BVH and its vertices after each build, which the "
           "repeated build's time includes (the splits include freeing the temporaries). A phase "
           "that grows more than its order allows pays for memory (the 1.6M build's arrays "
           "outgrow a 32 MiB L3: docs/performance.md).\n";
}

/// `--summary`: build times (medians) and their growth per 4x more triangles beside n log n's.
/// With 5 or more repetitions a step's growth gets a 95 % bootstrap interval.
void print_summary(const bench::Measured& m, std::ostream& out) {
    const char* sizes[3] = {"dragon_100k", "dragon_400k", "dragon_1600k"};
    auto repeated = [&](int i) { return std::string("BM_BuildMedian/") + sizes[i]; };
    auto first = [&](int i) {
        return std::string("BM_BuildMedianFirst/") + sizes[i] + "/iterations:1";
    };
    auto triangles = [&](int i) {
        const std::optional<double> n = m.median_counter(repeated(i), "triangles");
        return n ? n : m.median_counter(first(i), "triangles");
    };
    out << "Median-split build of the dragon, subdivided, on "
        << bench::isa_label(bench::isa_in_use()) << "; median of the repetitions\n\n"
        << "| triangles | n log n, per 4x | repeated build | growth | growth, 95 % interval "
           "| first build of a process | growth |\n|---:|---:|---:|---:|---:|---:|---:|\n";
    for (int i = 0; i < 3; ++i) {
        const std::optional<double> n = triangles(i);
        if (!n) continue;  // neither build of this size was run
        std::optional<double> nlogn, growth, first_growth;
        std::optional<std::pair<double, double>> interval;
        if (const std::optional<double> n0 = i > 0 ? triangles(i - 1) : std::nullopt) {
            nlogn = (*n * std::log(*n)) / (*n0 * std::log(*n0));
            growth = bench::divide(m.median_ms(repeated(i)), m.median_ms(repeated(i - 1)));
            first_growth = bench::divide(m.median_ms(first(i)), m.median_ms(first(i - 1)));
            interval = bench::median_ratio_interval(m, repeated(i), repeated(i - 1));
        }
        const std::string interval_text = interval
                                              ? bench::figure_text(interval->first, "%.2fx") + "–" +
                                                    bench::figure_text(interval->second, "%.2fx")
                                              : "—";
        out << "| " << bench::figure_text(n, "%.0f") << " | " << bench::figure_text(nlogn, "%.2fx")
            << " | " << bench::figure_text(m.median_ms(repeated(i)), "%.1f ms") << " | "
            << bench::figure_text(growth, "%.2fx") << " | " << interval_text << " | "
            << bench::figure_text(m.median_ms(first(i)), "%.1f ms") << " | "
            << bench::figure_text(first_growth, "%.2fx") << " |\n";
    }
    out << "\nA growth within n log n's keeps the build's cost per triangle and level; the "
           "interval "
           "(5 or more repetitions of both sizes) says how sure the median is. First "
           "builds are one per process only when each size runs alone "
           "(--benchmark_filter=BM_BuildMedianFirst/dragon_1600k). The sizes run one after the "
           "other, so a slow minute moves one step's growth; "
           "--benchmark_enable_random_interleaving=true spreads it over all three.\n";
    print_phases(m, out);
}

}  // namespace
}  // namespace raylane

int main(int argc, char** argv) {
    if (!raylane::bench::choose_isas(argv[0])) return 2;
    return raylane::bench::run_benchmarks(argc, argv, raylane::print_summary);
}
