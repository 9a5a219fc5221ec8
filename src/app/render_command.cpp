// app: `raylane render [SCENE] [-o FILE] [--spp N] [--threads N] [--width W --height H] [--aov A]`.
// The output is written by write_output.h, which `assemble` shares.
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.h"
#include "app/part.h"
#include "app/write_output.h"
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
    bool exr_float = false;
};

std::string default_output(const RenderOptions& o) {
    // the file name without its extension, .obj.gz and .ply.gz whole
    const std::string name = std::filesystem::path(o.scene_path).filename().string();
    const size_t ext = is_model_file(o.scene_path)
                           ? mesh_extension(name).size()
                           : std::filesystem::path(name).extension().string().size();
    std::string stem = o.scene_path.empty() ? "builtin" : name.substr(0, name.size() - ext);
    if (o.aov != "color") stem += "-" + o.aov;
    return stem + (o.aov == "all" ? ".exr" : ".png");
}

int run_render(const RenderOptions& o) {
    RenderParams params;
    const bool all_aovs = o.aov == "all";  // colour, then the AOVs, as layers of one EXR
    if (!all_aovs && !parse_aov(o.aov, params.aov))
        throw InputError("--aov: unknown output \"" + o.aov +
                         "\" (use color, normal, depth, bvh-cost or all)");
    // -o is checked as the command line is read; the default output here, before the render
    const std::string output = o.output.empty() ? default_output(o) : o.output;
    if (all_aovs && image_format(output) != ImageFormat::exr)
        throw InputError(output +
                         ": --aov all writes its four outputs as the layers of one EXR; "
                         "use -o FILE.exr");
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
                params.spp, all_aovs ? "color, normal, depth and bvh-cost" : aov_name(params.aov));
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

    const auto render = [&](const RenderParams& p) {
        return o.path == "scalar" ? render_scalar(scene, accel, p) : render_packet(scene, accel, p);
    };
    RenderResult result = render(params);
    std::vector<AovFilm> films;
    films.push_back({params.aov, Film{}});
    for (Aov aov : {Aov::normal, Aov::depth, Aov::bvh_cost}) {
        if (!all_aovs) break;
        RenderParams p = params;
        p.aov = aov;
        p.progress_label = aov_name(aov);
        films.push_back({aov, render(p).film});
    }
    const bool colour = params.aov == Aov::color;
    const uint64_t samples =
        uint64_t(scene.camera.width) * uint64_t(scene.camera.height) * uint64_t(params.spp);
    const std::vector<std::string> warnings =
        colour ? render_warnings(result.film, result.stats, samples) : std::vector<std::string>{};
    // PNG and PFM as they were; an EXR holds the raw films and what made them
    const bool raw = !colour && image_format(output) != ImageFormat::png;
    OutputOptions out;
    out.tonemap = scene.tonemap;
    out.threads = params.threads;
    out.exr_float = o.exr_float;
    if (image_format(output) == ImageFormat::exr) {
        PartInfo info = make_part_info(scene, params, o.path, o.bvh);
        if (all_aovs) set_part_setting(info, "aov", "all");
        out.attributes = frame_attributes(info);
    }
    films[0].film = std::move(result.film);
    const std::string scale = write_render_output(output, std::move(films), out);

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
    cmd->add_option("-o,--output", o->output,
                    "image to write (.png, .pfm or .exr; default SCENE.png)")
        ->check(image_output());
    cmd->add_flag("--exr-float", o->exr_float,
                  "EXR output: 32-bit floats (default: 16-bit halves)");
    cmd->add_option("--spp", o->spp, "samples per pixel (default: the scene's)")
        ->check(CLI::Range(1, 1 << 20));
    add_threads_option(cmd, o->threads);
    cmd->add_option("--width", o->width, "image width (alone: keeps the aspect ratio)")
        ->check(CLI::Range(1, max_film_side));
    cmd->add_option("--height", o->height, "image height (alone: keeps the aspect ratio)")
        ->check(CLI::Range(1, max_film_side));
    cmd->add_option("--aov", o->aov,
                    "output: color, normal, depth, bvh-cost, or all (as layers of one .exr)")
        ->check(CLI::IsMember({"color", "normal", "depth", "bvh-cost", "all"}));
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
