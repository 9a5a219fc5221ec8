// app: `raylane compare SCENE`: both paths with the same samples; differences and speed-up
// (raylane::Scene::compare of the public API).
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "raylane/scene.h"

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
    const Scene scene = load_command_scene(o.scene_path, o.bvh);
    CompareSettings settings;
    settings.width = o.width, settings.height = o.height, settings.spp = o.spp;
    settings.threads = o.threads, settings.repeats = o.repeats;
    settings.tolerance = o.tolerance, settings.id_allowance = o.id_allowance;
    settings.progress = !o.quiet;
    // timed as `report` times: one untimed 1-spp render per path first, then the paths in turn,
    // `repeats` times, the median of each; the images are the first run's
    const Comparison c = scene.compare(settings);
    std::printf("scene        %s (%dx%d, %d spp)\n", scene.source().c_str(), c.width, c.height,
                c.spp);
    std::printf("bvh          %s\n", o.bvh == "sah" ? "binned SAH" : "median split");
    std::printf("timing       median of %d run%s per path, after an untimed warm-up\n", o.repeats,
                o.repeats == 1 ? "" : "s");
    std::printf("scalar       %.1f ms\n", c.scalar_ms);
    std::printf("packet       %.1f ms (%s, W = %d)\n", c.packet_ms, c.instruction_set.c_str(),
                c.packet_width);
    std::printf("speed-up     %.2fx\n", c.scalar_ms / c.packet_ms);
    std::printf("max |diff|   %.3g\n", c.max_abs_diff);
    std::printf("mean |diff|  %.3g\n", c.mean_abs_diff);
    std::printf("RMSE         %.3g\n", c.rmse);
    std::printf("PSNR         %.1f dB\n", c.psnr_db);
    std::printf("> 1/255      %zu of %zu pixels\n", c.pixels_over_1_255, c.pixels);
    std::printf("hit ids      %zu of %zu primary hits differ\n", c.hit_id_mismatches, c.pixels);
    std::printf("NaN / Inf    scalar %llu / %llu, packet %llu / %llu samples\n",
                static_cast<unsigned long long>(c.scalar_nan_samples),
                static_cast<unsigned long long>(c.scalar_inf_samples),
                static_cast<unsigned long long>(c.packet_nan_samples),
                static_cast<unsigned long long>(c.packet_inf_samples));
    // strict: a NaN or infinite sample in either path is a failure, as in the tests
    if (c.scalar_shadow_rays != c.packet_shadow_rays)
        std::printf("shadow rays  %llu scalar, %llu packet\n",
                    static_cast<unsigned long long>(c.scalar_shadow_rays),
                    static_cast<unsigned long long>(c.packet_shadow_rays));
    std::printf("result       %s (tolerance %.3g, id allowance %zu)\n",
                c.agree ? "agree" : "DIFFER", o.tolerance, o.id_allowance);
    return c.agree ? 0 : 1;
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
