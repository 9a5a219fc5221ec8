// Benchmarks of the image writers, on the rendered 1920x1080 frame of scenes/dragon.json: the
// sRGB bytes (encode_film, the table), and the whole PNG in memory with Raylane's parallel zlib
// stream and with stb_image_write's own (compiled here, static, at the level Raylane used
// before: 4, which stb raises to 5), each with the file's size as a counter. 1 and 2 threads.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <cstdlib>
#include <vector>

#include "image/film.h"
#include "io/load_scene.h"
#include "render/render_packet.h"
#include "support/isa_sets.h"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace raylane {
namespace {

const Film* dragon_film() {
    static Film* film = []() -> Film* {
        try {
            const SceneData scene =
                load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/dragon.json");
            const Accel accel = build_accel(scene, BuildParams{});
            RenderParams params;
            params.progress = false;
            return new Film(render_packet(scene, accel, params).film);
        } catch (const std::exception&) {
            return nullptr;
        }
    }();
    return film;
}

template <class Body>
void in_arena(benchmark::State& state, Body&& body) {
    tbb::task_arena arena(static_cast<int>(state.range(0)));
    arena.execute(body);
}

void BM_EncodeFilm(benchmark::State& state) {
    const Film* film = dragon_film();
    if (!film) return state.SkipWithError("scenes/dragon.json or its model not found");
    in_arena(state, [&] {
        for (auto _ : state) benchmark::DoNotOptimize(encode_film(*film, Encoding::srgb).data());
    });
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(film->pixels.size() * 12));
}

/// The PNG in memory: encode_png (the sRGB bytes, stb's chunks and filters, deflate.h's zlib
/// stream), or the same bytes through stb_image_write's own zlib.
void png(benchmark::State& state, bool stb_zlib) {
    const Film* film = dragon_film();
    if (!film) return state.SkipWithError("scenes/dragon.json or its model not found");
    const ImageBytes bytes = encode_film(*film, Encoding::srgb);
    size_t size = 0;
    in_arena(state, [&] {
        for (auto _ : state) {
            if (stb_zlib) {
                stbi_write_png_compression_level = 4;
                int n = 0;
                unsigned char* out = stbi_write_png_to_mem(bytes.data(), film->width * 3,
                                                           film->width, film->height, 3, &n);
                benchmark::DoNotOptimize(out);
                std::free(out);
                size = static_cast<size_t>(n);
            } else {
                const std::vector<uint8_t> out = encode_png(*film, Encoding::srgb);
                benchmark::DoNotOptimize(out.data());
                size = out.size();
            }
        }
    });
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(bytes.size()));
    state.counters["file_bytes"] = static_cast<double>(size);
}

void BM_Png(benchmark::State& state) { png(state, false); }
void BM_PngStbZlib(benchmark::State& state) { png(state, true); }

BENCHMARK(BM_EncodeFilm)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Png)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PngStbZlib)->ArgName("threads")->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace raylane

int main(int argc, char** argv) { return raylane::bench::run_plain_benchmarks(argc, argv); }
