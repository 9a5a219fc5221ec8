// app: `raylane compare SCENE`: both paths with the same samples; differences and speed-up.
#include <cstdio>
#include <memory>
#include <vector>

#include "app/commands.h"
#include "core/isa.h"
#include "render/primary_ids.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "report/compare.h"
#include "report/report_metrics.h"

namespace raylane {
namespace {

struct CompareOptions {
    std::string scene_path, bvh = "median";
    int spp = 0, threads = 0, width = 0, height = 0, repeats = 3;
    double tolerance = 2e-3;
    size_t id_allowance = 0;
    bool quiet = false;
};

int run_compare(const CompareOptions& o) {
    SceneData scene = load_command_scene(o.scene_path);
    apply_resolution(scene.camera, o.width, o.height);
    const Accel accel = build_accel(scene, build_params(o.bvh));
    RenderParams params;
    params.spp = o.spp > 0 ? o.spp : scene.camera.spp;
    params.threads = worker_threads(o.threads);
    params.progress = !o.quiet;
    std::printf("scene        %s (%dx%d, %d spp)\n", scene.source.c_str(), scene.camera.width,
                scene.camera.height, params.spp);
    std::fflush(stdout);  // before the progress lines
    // timed as `report` times: one untimed 1-spp render per path first, then the paths in
    // turn, `repeats` times, the median of each; the images are the first run's (every run
    // renders the same samples)
    RenderParams warm = params;
    warm.spp = 1;
    warm.progress = false;
    (void)render_scalar(scene, accel, warm);
    (void)render_packet(scene, accel, warm);
    RenderResult scalar, packet;
    std::vector<double> scalar_s, packet_s;
    for (int r = 0; r < o.repeats; ++r) {
        params.progress_label = "scalar";
        RenderResult a = render_scalar(scene, accel, params);
        params.progress_label = "packet";
        RenderResult b = render_packet(scene, accel, params);
        scalar_s.push_back(a.stats.seconds), packet_s.push_back(b.stats.seconds);
        if (r == 0) scalar = std::move(a), packet = std::move(b);
    }
    const double scalar_median = median(scalar_s), packet_median = median(packet_s);
    const ImageDiff d = diff_images(scalar.film, packet.film);
    const size_t ids = primary_id_mismatches(scene, accel);
    const size_t pixels = scalar.film.pixels.size();

    std::printf("bvh          %s\n", o.bvh == "sah" ? "binned SAH" : "median split");
    std::printf("timing       median of %d run%s per path, after an untimed warm-up\n", o.repeats,
                o.repeats == 1 ? "" : "s");
    std::printf("scalar       %.1f ms\n", 1000.0 * scalar_median);
    std::printf("packet       %.1f ms (%s, W = %d)\n", 1000.0 * packet_median,
                isa_name(active_isa()), isa_width(active_isa()));
    std::printf("speed-up     %.2fx\n", scalar_median / packet_median);
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
        "compare",
        "render with both paths and report their difference and speed-up (timed as report "
        "times: warmed up, the median of --repeats runs per path)");
    cmd->add_option("scene", o->scene_path,
                    "scene JSON file or model (.obj, .ply; default: the built-in scene)")
        ->check(existing_scene_file());
    cmd->add_option("--spp", o->spp, "samples per pixel (default: the scene's)")
        ->check(whole_in(1, 1 << 20));
    add_threads_option(cmd, o->threads);
    cmd->add_option("--width", o->width, "image width")->check(whole_in(1, max_film_side));
    cmd->add_option("--height", o->height, "image height")->check(whole_in(1, max_film_side));
    add_bvh_option(cmd, o->bvh);
    cmd->add_option("--tolerance", o->tolerance,
                    "largest allowed per-channel difference (linear; default 2e-3)")
        ->check(finite_non_negative());
    cmd->add_option("--id-allowance", o->id_allowance, "primary hits allowed to differ (default 0)")
        ->transform(whole_number());
    cmd->add_option("--repeats", o->repeats, "timed runs per path; time = median (default 3)")
        ->check(whole_in(1, 100));
    cmd->add_flag("-q,--quiet", o->quiet, "no progress on stderr");
    cmd->callback([o, &exit_code] { exit_code = run_compare(*o); });
}

}  // namespace raylane
