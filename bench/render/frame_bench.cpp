// Benchmarks of render/: full frames of scenes/dragon.json (1920x1080, 1 sample, two point
// lights with shadows), scalar and packet path, on 1 and 2 threads; the packet path on every
// instruction set raced (support/isa_sets.h), also through the binned SAH build (a comparison
// option, `--bvh sah`).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "core/isa.h"
#include "io/load_scene.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "support/isa_sets.h"
#include "support/summary.h"

namespace raylane {
namespace {

struct Loaded {
    SceneData scene;
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

/// A frame on the scalar path, or with `packet` on the packet path of the set `isa`.
void frame(benchmark::State& state, int threads, bool packet, Isa isa, BvhBuild build) {
    const Loaded* l = dragon_scene();
    if (!l) {
        state.SkipWithError("scenes/dragon.json or its model not found");
        return;
    }
    use_isa(isa);
    const Accel& accel = build == BvhBuild::sah ? l->accel_sah : l->accel;
    RenderParams params;
    params.threads = threads;
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

/// BM_Frame_Scalar/threads:1 (on the set in use), and per set raced BM_Frame_Packet_avx2/
/// threads:1 and BM_Frame_PacketSah_avx2/threads:1 (through the binned SAH build).
void register_all() {
    for (int threads : {1, 2}) {
        auto add = [&](const std::string& name, bool packet, Isa isa, BvhBuild build) {
            benchmark::RegisterBenchmark(
                ("BM_Frame_" + name + "/threads:" + std::to_string(threads)).c_str(), frame,
                threads, packet, isa, build)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
        };
        add("Scalar", false, bench::isa_in_use(), BvhBuild::median);
        for (Isa isa : bench::raced_isas()) {
            add(std::string("Packet_") + isa_name(isa), true, isa, BvhBuild::median);
            add(std::string("PacketSah_") + isa_name(isa), true, isa, BvhBuild::sah);
        }
    }
}

/// `--summary`: the frame's medians per set, and the packet path's speed-up over the scalar path
/// (scalar time / packet time).
void print_summary(const bench::Measured& m, std::ostream& out) {
    auto ms = [&](const std::string& path, int threads) {
        return m.median_ms("BM_Frame_" + path + "/threads:" + std::to_string(threads) +
                           "/real_time");
    };
    auto packet = [&](Isa isa, int threads) {
        return ms(std::string("Packet_") + isa_name(isa), threads);
    };
    out << "scenes/dragon.json, 1920x1080, 1 sample; median of the repetitions\n\n"
        << "| instruction set | threads | scalar | packet | packet, SAH | packet speed-up |\n"
        << "|---|---:|---:|---:|---:|---:|\n";
    for (Isa isa : bench::raced_isas())
        for (int threads : {1, 2})
            out << "| " << bench::isa_label(isa) << " | " << threads << " | "
                << bench::figure_text(ms("Scalar", threads), "%.1f ms") << " | "
                << bench::figure_text(packet(isa, threads), "%.1f ms") << " | "
                << bench::figure_text(ms(std::string("PacketSah_") + isa_name(isa), threads),
                                      "%.1f ms")
                << " | " << bench::ratio_text(ms("Scalar", threads), packet(isa, threads))
                << " |\n";
    bench::print_isas_not_raced(out);
}

}  // namespace
}  // namespace raylane

int main(int argc, char** argv) {
    if (!raylane::bench::choose_isas(argv[0])) return 2;
    raylane::register_all();
    return raylane::bench::run_benchmarks(argc, argv, raylane::print_summary);
}
