// app: `raylane render [SCENE] [-o FILE] [--spp N] [--threads N] [--width W --height H] [--aov A]
// [--frames A..B] [--crop X0 Y0 X1 Y1 | --tile I/N]`: the options and the plain render, frame
// after frame; under mpirun, distribute/render_mpi.cpp. The files are written by write_output.h and
// part.h, which `assemble` shares.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.h"
#include "core/error.h"
#include "distribute/render_job.h"
#include "io/load_mesh.h"
#include "io/model_scene.h"
#include "report/warnings.h"
#include "scene/camera_path.h"

namespace raylane {
namespace {

struct RenderOptions {
    std::string scene_path, output, aov = "color", path = "packet", bvh = "median";
    std::string frames, tile;
    std::vector<int> crop;
    int spp = 0, threads = 0, width = 0, height = 0;
    uint32_t seed = 0;
    bool quiet = false;
    bool strict = false;
    bool exr_float = false;
};

/// SCENE.png (SCENE-AOV.png), with _I-N for part I of N, _crop for a crop, _%04d when several
/// frames render; .exr for parts and --aov all.
std::string default_output(const RenderOptions& o, bool frames) {
    // the file name without its extension, .obj.gz and .ply.gz whole
    const std::string name = std::filesystem::path(o.scene_path).filename().string();
    const size_t ext = is_model_file(o.scene_path)
                           ? mesh_extension(name).size()
                           : std::filesystem::path(name).extension().string().size();
    std::string stem = o.scene_path.empty() ? "builtin" : name.substr(0, name.size() - ext);
    if (o.aov != "color") stem += "-" + o.aov;
    if (!o.tile.empty()) {  // part I of N: SCENE_I-N
        std::string part = o.tile;
        std::replace(part.begin(), part.end(), '/', '-');
        stem += "_" + part;
    }
    if (!o.crop.empty()) stem += "_crop";
    if (frames) stem += "_%04d";
    // --aov all and the parts of a frame are EXR files
    return stem + (o.aov == "all" || !o.crop.empty() || !o.tile.empty() ? ".exr" : ".png");
}

/// The job: the scene at its resolution, the frames and part to render, the renderer's options.
RenderJob make_job(const RenderOptions& o, SceneData scene, const std::vector<Aov>& aovs) {
    RenderJob job;
    job.scene = std::move(scene);
    apply_resolution(job.scene.camera, o.width, o.height);
    job.still = job.scene.camera;
    if (!o.frames.empty())
        parse_frames(o.frames, frame_count(job.scene.camera_path), job.first_frame, job.last_frame);
    job.region = parse_region(o.crop, o.tile, job.still.width, job.still.height);
    job.output = o.output.empty() ? default_output(o, job.first_frame != job.last_frame) : o.output;
    if (o.output.empty()) {
        if (const std::string why = image_output()(job.output); !why.empty())
            throw InputError("output: " + why);
    }
    if (job.first_frame != job.last_frame && !has_frame_number(job.output)) {
        throw InputError("-o " + job.output + ": " +
                         std::to_string(job.last_frame - job.first_frame + 1) +
                         " frames need a frame number in the file name, e.g. out/frame_%04d.png");
    }
    job.aovs = aovs;
    job.params.aov = aovs[0];
    job.params.spp = o.spp > 0 ? o.spp : job.still.spp;
    job.params.threads = worker_threads(o.threads);
    job.params.seed = o.seed;
    job.params.progress = !o.quiet;
    job.quiet = o.quiet;
    job.scalar = o.path == "scalar";
    job.exr_float = o.exr_float;
    job.strict = o.strict;
    job.bvh = o.bvh;
    job.info = make_part_info(job.scene, job.params, o.path, o.bvh);
    if (aovs.size() > 1) set_part_setting(job.info, "aov", "all");
    return job;
}

int run_render(const RenderOptions& o) {
    // --aov all: colour, then the AOVs, as layers of one EXR
    std::vector<Aov> aovs{Aov::color, Aov::normal, Aov::depth, Aov::bvh_cost};
    if (o.aov != "all") {
        aovs.resize(1);
        if (!parse_aov(o.aov, aovs[0]))
            throw InputError("--aov: unknown output \"" + o.aov +
                             "\" (use color, normal, depth, bvh-cost or all)");
    }
    if (o.aov == "all" && !o.output.empty() && image_format(o.output) != ImageFormat::exr)
        throw InputError(o.output +
                         ": --aov all writes its four outputs as the layers of one EXR; "
                         "use -o FILE.exr");
    if (launched_by_mpi()) {
#ifdef RAYLANE_MPI
        return render_over_mpi([&] {
            const double t_load = now_seconds();
            RenderJob job = make_job(o, load_command_scene(o.scene_path), aovs);
            job.load_ms = elapsed_ms(t_load);
            return job;
        });
#else
        throw InputError(
            "started by mpirun, but this raylane was built without MPI: run it alone (it "
            "uses every core), or build it where Open MPI is installed (libopenmpi-dev)");
#endif
    }
    const double t_load = now_seconds();
    RenderJob job = make_job(o, load_command_scene(o.scene_path), aovs);
    job.load_ms = elapsed_ms(t_load);
    print_header(job, 1);

    const double t_build = now_seconds();
    job.accel = build_accel(job.scene, build_params(o.bvh));
    job.build_ms = elapsed_ms(t_build);
    for (const std::string& w : scene_warnings(job.scene, job.accel))
        std::printf("warning    %s\n", w.c_str());
    std::fflush(stdout);

    RenderStats total;
    const double t_frames = now_seconds();
    for (int frame = job.first_frame; frame <= job.last_frame; ++frame) {
        PartResult part = render_part(job, frame, job.region);
        write_frame(job, frame, std::move(part.films), part.stats);
        total.add_counts(part.stats);
    }
    if (job.first_frame != job.last_frame && !job.quiet) {
        std::printf("frames     %d in %.1f s (load %.1f ms, build %.1f ms)\n",
                    job.last_frame - job.first_frame + 1, elapsed_ms(t_frames) / 1000.0,
                    job.load_ms, job.build_ms);
    }
    return strict_exit_code(job, total);
}

}  // namespace

void add_render_command(CLI::App& app, int& exit_code) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "render a scene (the built-in scene without one)");
    cmd->add_option("scene", o->scene_path, "scene JSON file or model (.obj, .ply)")
        ->check(existing_scene_file());
    cmd->add_option("-o,--output", o->output,
                    "image to write (.png, .pfm or .exr; default SCENE.png); with --frames, a "
                    "name with a frame number such as frame_%04d.png")
        ->check(image_output());
    cmd->add_flag("--exr-float", o->exr_float,
                  "EXR output: 32-bit floats (default: 16-bit halves; parts are always floats)");
    cmd->add_option("--spp", o->spp, "samples per pixel (default: the scene's)")
        ->check(whole_in(1, 1 << 20));
    add_threads_option(cmd, o->threads);
    cmd->add_option("--width", o->width, "image width (alone: keeps the aspect ratio)")
        ->check(whole_in(1, max_film_side));
    cmd->add_option("--height", o->height, "image height (alone: keeps the aspect ratio)")
        ->check(whole_in(1, max_film_side));
    cmd->add_option("--aov", o->aov,
                    "output: color, normal, depth, bvh-cost, or all (as layers of one .exr)")
        ->check(CLI::IsMember({"color", "normal", "depth", "bvh-cost", "all"}));
    cmd->add_option("--seed", o->seed, "seed of the sample hash");
    cmd->add_option("--path", o->path, "renderer: packet (default) or scalar (the reference)")
        ->check(CLI::IsMember({"packet", "scalar"}));
    add_bvh_option(cmd, o->bvh);
    cmd->add_option("--frames", o->frames,
                    "frames A..B (or A, or all) of the scene's camera animation; -o then holds a "
                    "frame number, e.g. out/frame_%04d.png");
    cmd->add_option("--crop", o->crop,
                    "render only pixels X0..X1-1, Y0..Y1-1 of the frame (to an .exr: a part for "
                    "`raylane assemble`)")
        ->expected(4);
    cmd->add_option("--tile", o->tile,
                    "render only part I of N of the frame (0 <= I < N), cut along the tile grid "
                    "(to an .exr: a part for `raylane assemble`)");
    cmd->add_flag("-q,--quiet", o->quiet,
                  "print nothing but warnings and errors (no progress, no summary)");
    cmd->add_flag("--strict", o->strict,
                  "exit with status 3 when any sample is NaN or infinite (the image is written, "
                  "without them)");
    cmd->callback([o, &exit_code] { exit_code = run_render(*o); });
}

}  // namespace raylane
