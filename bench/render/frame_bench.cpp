// Benchmarks of render/: full frames of scenes/dragon.json (1920x1080, 1 sample, two point
// lights with shadows), scalar and packet path, on 1 and 2 threads; the packet path also through
// the binned SAH build (a comparison option, `--bvh sah`).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>

#include "io/load_scene.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "support/summary.h"

namespace raylane {
namespace {

struct Loaded {
    Scene scene;
    Accel accel;      ///< the median split (the report's build, the default)
    Accel accel_sah;  ///< binned SAH
};

const Loaded* dragon_scene() {
    static Loaded* loaded = []() -> Loaded* {
        const std::string path = std::string(RAYLANE_SOURCE_DIR) + "/scenes/dragon.json";
        try {
            auto* l = new Loaded{load_scene(path), {}, {}};
            l->accel = build_accel(l->scene, BuildParams{});
            l->accel_sah = build_accel(l->scene, BuildParams{.method = BvhBuild::sah});
            return l;
        } catch (const std::exception&) {
            return nullptr;
        }
    }();
    return loaded;
}

void frame(benchmark::State& state, bool packet, BvhBuild build = BvhBuild::median) {
    const Loaded* l = dragon_scene();
    if (!l) {
        state.SkipWithError("scenes/dragon.json or its model not found");
        return;
    }
    const Accel& accel = build == BvhBuild::sah ? l->accel_sah : l->accel;
    RenderParams params;
    params.threads = static_cast<int>(state.range(0));
    uint64_t rays = 0;
    for (auto _ : state) {
        RenderResult r = packet ? render_packet(l->scene, accel, params)
                                : render_scalar(l->scene, accel, params);
        rays += r.stats.total_rays();
        benchmark::DoNotOptimize(r.film.pixels.data());
    }
    state.counters["rays/s"] =
        benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}

void BM_Frame_Scalar(benchmark::State& state) { frame(state, false); }
void BM_Frame_Packet(benchmark::State& state) { frame(state, true); }
void BM_Frame_PacketSah(benchmark::State& state) { frame(state, true, BvhBuild::sah); }

BENCHMARK(BM_Frame_Scalar)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Frame_Packet)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Frame_PacketSah)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// `--summary`: the frame's medians, the packet path's speed-up over the scalar path (scalar
/// time / packet time), and the frame's target (< 30 ms on 2 threads).
void print_summary(const bench::Measured& m, std::ostream& out) {
    auto ms = [&](const char* path, int threads) {
        return m.median_ms(std::string("BM_Frame_") + path + "/threads:" + std::to_string(threads) +
                           "/real_time");
    };
    out << "scenes/dragon.json, 1920x1080, 1 sample; median of the repetitions\n\n"
        << "| threads | scalar | packet | packet, SAH | packet speed-up |\n"
        << "|---:|---:|---:|---:|---:|\n";
    for (int threads : {1, 2})
        out << "| " << threads << " | " << bench::figure_text(ms("Scalar", threads), "%.1f ms")
            << " | " << bench::figure_text(ms("Packet", threads), "%.1f ms") << " | "
            << bench::figure_text(ms("PacketSah", threads), "%.1f ms") << " | "
            << bench::ratio_text(ms("Scalar", threads), ms("Packet", threads)) << " |\n";
    const std::optional<double> frame = ms("Packet", 2);
    out << "\nTarget:\n- dragon frame, packet path, 2 threads < 30 ms: "
        << bench::verdict_below(frame, 30.0) << " (" << bench::figure_text(frame, "%.1f ms")
        << ")\n";
}

}  // namespace
}  // namespace raylane

int main(int argc, char** argv) {
    return raylane::bench::run_benchmarks(argc, argv, raylane::print_summary);
}
