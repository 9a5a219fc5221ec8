// Benchmarks of the shading features: for scenes that use few and many features, the scalar
// path, the packet path with the kernel specialised to the scene's features, and the packet
// path with the all-features kernel. On 1 and 2 threads (the argument); the report figures at 320
// pixels wide. The packet path runs on the instruction set in use (RAYLANE_ISA, else the widest
// this CPU runs).
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include "io/load_scene.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "support/isa_sets.h"

namespace raylane {
namespace {

struct Loaded {
    SceneData scene;
    Accel accel;
};

/// The scene file, at `width` pixels wide (0: its own size); nullptr when it cannot load.
const Loaded* scene(const std::string& name, int width) {
    static std::map<std::string, Loaded*> cache;
    auto it = cache.find(name);
    if (it != cache.end()) return it->second;
    Loaded* l = nullptr;
    try {
        l = new Loaded{load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name), {}};
        Camera& c = l->scene.camera;
        if (width > 0) {
            c.height = c.height * width / c.width;
            c.width = width;
        }
        l->accel = build_accel(l->scene, BuildParams{});
    } catch (const std::exception&) {
        l = nullptr;
    }
    cache[name] = l;
    return l;
}

enum class Contender { scalar, packet, packet_generic };

void render_scene(benchmark::State& state, const char* name, int width, Contender who) {
    const Loaded* l = scene(name, width);
    if (!l) {
        state.SkipWithError("scene or model not found");
        return;
    }
    RenderParams params;
    params.threads = static_cast<int>(state.range(0));
    params.spp = 1;
    params.generic_kernel = who == Contender::packet_generic;
    uint64_t rays = 0;
    for (auto _ : state) {
        RenderResult r = who == Contender::scalar ? render_scalar(l->scene, l->accel, params)
                                                  : render_packet(l->scene, l->accel, params);
        rays += r.stats.total_rays();
        benchmark::DoNotOptimize(r.film.pixels.data());
    }
    state.counters["rays/s"] =
        benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}

#define RAYLANE_SHADING_BENCH(label, file, width)                                                 \
    void BM_##label##_Scalar(benchmark::State& s) {                                               \
        render_scene(s, file, width, Contender::scalar);                                          \
    }                                                                                             \
    void BM_##label##_Packet(benchmark::State& s) {                                               \
        render_scene(s, file, width, Contender::packet);                                          \
    }                                                                                             \
    void BM_##label##_PacketGeneric(benchmark::State& s) {                                        \
        render_scene(s, file, width, Contender::packet_generic);                                  \
    }                                                                                             \
    BENCHMARK(BM_##label##_Scalar)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime(); \
    BENCHMARK(BM_##label##_Packet)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime(); \
    BENCHMARK(BM_##label##_PacketGeneric)                                                         \
        ->Arg(1)                                                                                  \
        ->Arg(2)                                                                                  \
        ->Unit(benchmark::kMillisecond)                                                           \
        ->UseRealTime();

// no kernel features: diffuse only (the built-in shapes), diffuse + Phong (the dragon frame,
// the built-in scene)
RAYLANE_SHADING_BENCH(Diffuse, "diffuse_shapes.json", 640)
RAYLANE_SHADING_BENCH(Dragon, "dragon.json", 960)
RAYLANE_SHADING_BENCH(Builtin, "builtin.json", 640)
// glossy rays and area lights; glass; glass mesh with an area light; mirrors
RAYLANE_SHADING_BENCH(GlossySphere, "fig01b_glossy_sphere.json", 320)
RAYLANE_SHADING_BENCH(GlassSphere, "fig05_refractive_sphere.json", 320)
RAYLANE_SHADING_BENCH(GlassBunny, "fig10_glass_bunny.json", 320)
RAYLANE_SHADING_BENCH(MirrorSpheres, "fig08b_dof_middle.json", 320)

}  // namespace
}  // namespace raylane

int main(int argc, char** argv) { return raylane::bench::run_plain_benchmarks(argc, argv); }
