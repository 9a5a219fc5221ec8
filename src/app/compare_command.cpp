// app: `raylane compare SCENE`: both paths with the same samples; differences and speed-up.
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "render/compare.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "simd/simd.h"

namespace raylane {
namespace {

struct CompareOptions {
    std::string scene_path, bvh = "median";
    int spp = 0, threads = 0, width = 0, height = 0;
    double tolerance = 2e-3;
    size_t id_allowance = 0;
    bool quiet = false;
};

int run_compare(const CompareOptions& o) {
    Scene scene = load_command_scene(o.scene_path);
    apply_resolution(scene.camera, o.width, o.height);
    const Accel accel = build_accel(scene, build_params(o.bvh));
    RenderParams params;
    params.spp = o.spp > 0 ? o.spp : scene.camera.spp;
    params.threads = worker_threads(o.threads);
    params.progress = !o.quiet;
    std::printf("scene        %s (%dx%d, %d spp)\n", scene.source.c_str(), scene.camera.width,
                scene.camera.height, params.spp);
    std::fflush(stdout);  // before the progress lines
    params.progress_label = "scalar";
    const RenderResult scalar = render_scalar(scene, accel, params);
    params.progress_label = "packet";
    const RenderResult packet = render_packet(scene, accel, params);
    const ImageDiff d = diff_images(scalar.film, packet.film);
    const size_t ids = primary_id_mismatches(scene, accel);
    const size_t pixels = scalar.film.pixels.size();

    std::printf("scalar       %.1f ms\n", 1000.0 * scalar.stats.seconds);
    std::printf("packet       %.1f ms (W = %d)\n", 1000.0 * packet.stats.seconds, native_width);
    std::printf("speed-up     %.2fx\n", scalar.stats.seconds / packet.stats.seconds);
    std::printf("max |diff|   %.3g\n", d.max_abs);
    std::printf("mean |diff|  %.3g\n", d.mean_abs);
    std::printf("RMSE         %.3g\n", d.rmse);
    std::printf("PSNR         %.1f dB\n", d.psnr_db);
    std::printf("> 1/255      %zu of %zu pixels\n", d.pixels_over_8bit, pixels);
    std::printf("hit ids      %zu of %zu primary hits differ\n", ids, pixels);
    std::printf("NaN / Inf    scalar %llu / %llu, packet %llu / %llu samples\n",
                static_cast<unsigned long long>(scalar.stats.nan_samples),
                static_cast<unsigned long long>(scalar.stats.inf_samples),
                static_cast<unsigned long long>(packet.stats.nan_samples),
                static_cast<unsigned long long>(packet.stats.inf_samples));
    // strict: a NaN or infinite sample in either path is a failure, as in the tests
    const bool ok = d.max_abs <= o.tolerance && ids <= o.id_allowance &&
                    scalar.stats.shadow_rays == packet.stats.shadow_rays &&
                    scalar.stats.bad_samples() == 0 && packet.stats.bad_samples() == 0;
    if (scalar.stats.shadow_rays != packet.stats.shadow_rays)
        std::printf("shadow rays  %llu scalar, %llu packet\n",
                    static_cast<unsigned long long>(scalar.stats.shadow_rays),
                    static_cast<unsigned long long>(packet.stats.shadow_rays));
    std::printf("result       %s (tolerance %.3g, id allowance %zu)\n", ok ? "agree" : "DIFFER",
                o.tolerance, o.id_allowance);
    return ok ? 0 : 1;
}

}  // namespace

void add_compare_command(CLI::App& app, int& exit_code) {
    auto o = std::make_shared<CompareOptions>();
    CLI::App* cmd = app.add_subcommand(
        "compare", "render with both paths and report their difference and speed-up");
    cmd->add_option("scene", o->scene_path,
                    "scene JSON file or model (.obj, .ply; default: the built-in scene)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--spp", o->spp, "samples per pixel (default: the scene's)")
        ->check(CLI::Range(1, 1 << 20));
    add_threads_option(cmd, o->threads);
    cmd->add_option("--width", o->width, "image width")->check(CLI::Range(1, max_film_side));
    cmd->add_option("--height", o->height, "image height")->check(CLI::Range(1, max_film_side));
    add_bvh_option(cmd, o->bvh);
    cmd->add_option("--tolerance", o->tolerance,
                    "largest allowed per-channel difference (linear; default 2e-3)")
        ->check(finite_non_negative());
    cmd->add_option("--id-allowance", o->id_allowance, "primary hits allowed to differ (default 0)")
        ->transform(whole_number());
    cmd->add_flag("-q,--quiet", o->quiet, "no progress on stderr");
    cmd->callback([o, &exit_code] { exit_code = run_compare(*o); });
}

}  // namespace raylane
