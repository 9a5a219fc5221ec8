// app: `raylane render [SCENE] [-o FILE] [--spp N] [--threads N] [--width W --height H] [--aov A]`.
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.h"
#include "core/error.h"
#include "io/load_mesh.h"
#include "io/model_scene.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "render/warnings.h"
#include "scene/features.h"
#include "simd/simd.h"

namespace raylane {
namespace {

struct RenderOptions {
    std::string scene_path, output, aov = "color", path = "packet", bvh = "median";
    int spp = 0, threads = 0, width = 0, height = 0;
    uint32_t seed = 0;
    bool quiet = false;
    bool strict = false;
};

std::string default_output(const RenderOptions& o) {
    // the file name without its extension, .obj.gz and .ply.gz whole
    const std::string name = std::filesystem::path(o.scene_path).filename().string();
    const size_t ext = is_model_file(o.scene_path)
                           ? mesh_extension(name).size()
                           : std::filesystem::path(name).extension().string().size();
    std::string stem = o.scene_path.empty() ? "builtin" : name.substr(0, name.size() - ext);
    if (o.aov != "color") stem += "-" + o.aov;
    return stem + ".png";
}

int run_render(const RenderOptions& o) {
    RenderParams params;
    if (!parse_aov(o.aov, params.aov))
        throw InputError("--aov: unknown output \"" + o.aov +
                         "\" (use color, normal, depth or bvh-cost)");
    // -o is checked as the command line is read; the default output here, before the render
    const std::string output = o.output.empty() ? default_output(o) : o.output;
    if (o.output.empty()) {
        if (const std::string why = image_output()(output); !why.empty())
            throw InputError("output: " + why);
    }
    const double t_load = now_seconds();
    Scene scene = load_command_scene(o.scene_path);
    const double load_ms = elapsed_ms(t_load);
    apply_resolution(scene.camera, o.width, o.height);
    params.spp = o.spp > 0 ? o.spp : scene.camera.spp;
    params.threads = worker_threads(o.threads);
    params.seed = o.seed;
    params.progress = !o.quiet;
    const int threads = params.threads > 0 ? params.threads : tbb::info::default_concurrency();
    // what is being rendered, before the progress line
    std::printf("scene      %s\n", scene.source.c_str());
    std::printf("resolution %dx%d, %d spp, %s\n", scene.camera.width, scene.camera.height,
                params.spp, aov_name(params.aov));
    if (o.path == "scalar")
        std::printf("path       scalar, %d threads\n", threads);
    else
        std::printf("path       packet (W = %d), %d threads\n", native_width, threads);
    std::fflush(stdout);

    const double t_build = now_seconds();
    const Accel accel = build_accel(scene, build_params(o.bvh));
    const double build_ms = elapsed_ms(t_build);
    for (const std::string& w : scene_warnings(scene, accel))
        std::printf("warning    %s\n", w.c_str());
    std::fflush(stdout);

    RenderResult result = o.path == "scalar" ? render_scalar(scene, accel, params)
                                             : render_packet(scene, accel, params);
    const bool colour = params.aov == Aov::color;
    const uint64_t samples =
        uint64_t(scene.camera.width) * uint64_t(scene.camera.height) * uint64_t(params.spp);
    const std::vector<std::string> warnings =
        colour ? render_warnings(result.film, result.stats, samples) : std::vector<std::string>{};
    const bool report_look = colour && scene.tonemap == Tonemap::report;
    // in place: the rendered film is not needed afterwards (a copy is 25 MB of fresh pages).
    // A PFM holds an AOV's raw values (scene units, counts); a PNG its mapping, named by `scale`.
    const bool raw = !colour && image_format(output) == ImageFormat::pfm;
    std::string scale;
    Film film;
    if (report_look) {
        film = hue_preserving_clamp(std::move(result.film));
    } else if (raw) {
        film = std::move(result.film);
    } else {
        AovView view = visualise_aov(std::move(result.film), params.aov);
        film = std::move(view.film);
        scale = std::move(view.scale);
    }
    // the bytes and the PNG's stream are made in parallel: on the threads --threads allows
    tbb::task_arena(params.threads > 0 ? params.threads : tbb::task_arena::automatic).execute([&] {
        write_image(output, film, colour && !report_look ? Encoding::srgb : Encoding::linear);
    });

    const RenderStats& s = result.stats;
    std::printf("features   %s\n", feature_names(scene_features(scene)).c_str());
    if (o.bvh != "median") std::printf("bvh        %s\n", o.bvh.c_str());
    std::printf("rays       %llu primary, %llu shadow",
                static_cast<unsigned long long>(s.primary_rays),
                static_cast<unsigned long long>(s.shadow_rays));
    if (s.reflection_rays > 0)
        std::printf(", %llu reflection", static_cast<unsigned long long>(s.reflection_rays));
    if (s.refraction_rays > 0)
        std::printf(", %llu refraction", static_cast<unsigned long long>(s.refraction_rays));
    if (s.glossy_rays > 0)
        std::printf(", %llu glossy", static_cast<unsigned long long>(s.glossy_rays));
    std::printf("\n");
    std::printf("time       load %.1f ms, build %.1f ms, render %.1f ms\n", load_ms, build_ms,
                1000.0 * s.seconds);
    std::printf("speed      %.2f Mrays/s\n",
                s.seconds > 0 ? double(s.total_rays()) / s.seconds * 1e-6 : 0.0);
    if (s.bad_samples() > 0)
        std::printf("warning    %llu NaN and %llu infinite samples were left out of their pixels\n",
                    static_cast<unsigned long long>(s.nan_samples),
                    static_cast<unsigned long long>(s.inf_samples));
    if (!scale.empty()) std::printf("scale      %s\n", scale.c_str());
    if (raw)
        std::printf("values     raw %s (docs/scene-format.md, Outputs)\n", aov_name(params.aov));
    for (const std::string& w : warnings) std::printf("warning    %s\n", w.c_str());
    std::printf("image      %s\n", output.c_str());
    if (o.strict && s.bad_samples() > 0) {
        std::fprintf(stderr, "raylane: %s: %llu NaN and %llu infinite samples (--strict)\n",
                     scene.source.c_str(), static_cast<unsigned long long>(s.nan_samples),
                     static_cast<unsigned long long>(s.inf_samples));
        return 3;
    }
    return 0;
}

}  // namespace

void add_render_command(CLI::App& app, int& exit_code) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "render a scene (the built-in scene without one)");
    cmd->add_option("scene", o->scene_path, "scene JSON file or model (.obj, .ply)")
        ->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", o->output, "image to write (.png or .pfm; default SCENE.png)")
        ->check(image_output());
    cmd->add_option("--spp", o->spp, "samples per pixel (default: the scene's)")
        ->check(CLI::Range(1, 1 << 20));
    add_threads_option(cmd, o->threads);
    cmd->add_option("--width", o->width, "image width (alone: keeps the aspect ratio)")
        ->check(CLI::Range(1, max_film_side));
    cmd->add_option("--height", o->height, "image height (alone: keeps the aspect ratio)")
        ->check(CLI::Range(1, max_film_side));
    cmd->add_option("--aov", o->aov, "output: color, normal, depth or bvh-cost")
        ->check(CLI::IsMember({"color", "normal", "depth", "bvh-cost"}));
    cmd->add_option("--seed", o->seed, "seed of the sample hash");
    cmd->add_option("--path", o->path, "renderer: packet (default) or scalar (the reference)")
        ->check(CLI::IsMember({"packet", "scalar"}));
    add_bvh_option(cmd, o->bvh);
    cmd->add_flag("-q,--quiet", o->quiet, "no progress on stderr");
    cmd->add_flag("--strict", o->strict,
                  "exit with status 3 when any sample is NaN or infinite (the image is written, "
                  "without them)");
    cmd->callback([o, &exit_code] { exit_code = run_render(*o); });
}

}  // namespace raylane
