// app: `raylane report SCENE... [--out-dir DIR] [--reference-spp N] [--spp-list 1,2,4,...]
// [--paths packet,scalar] [--repeats K]`: error against run time. The options, the reference
// (analytic, cached or rendered), progress on stderr and where the files go; the sweep, its
// table, CSV and plot are report/'s (report_sweep.h, report_table.h, report_csv.h, report_plot.h).
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "app/commands.h"
#include "core/error.h"
#include "core/isa.h"
#include "render/progress.h"
#include "report/plot_svg.h"
#include "report/report_analytic.h"
#include "report/report_cache.h"
#include "report/report_csv.h"
#include "report/report_plot.h"
#include "report/report_speedups.h"
#include "report/report_sweep.h"
#include "report/report_table.h"

namespace raylane {
namespace {

struct ReportOptions {
    std::vector<std::string> scenes;
    std::string out_dir = "out/report";
    std::string reference_path = "packet";
    std::vector<int> spp_list{1, 2, 4, 8, 16, 32, 64};
    std::vector<std::string> paths{"packet", "scalar"};
    int reference_spp = 0;  // 0 = 100 x the largest sweep value
    int threads = 0, width = 0, height = 0, repeats = 3;
    bool fresh_reference = false, quiet = false;
};

std::string cpu_model() {
    std::ifstream f("/proc/cpuinfo");
    std::string line;
    while (std::getline(f, line))
        if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos)
            return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

/// Compiler, assertions, sanitizers and packet width: what the "build flags" line shows.
std::string build_description() {
    std::string s = "GCC-compatible " __VERSION__;
#ifdef NDEBUG
    s += ", NDEBUG";
#else
    s += ", assertions on";
#endif
#ifdef RAYLANE_SANITIZED
    s += ", sanitizers";
#endif
    s += ", -ffp-contract=off, " + std::string(isa_name(active_isa())) +
         ", W = " + std::to_string(isa_width(active_isa()));
    return s;
}

/// The build plus when the running executable was made (a rebuilt renderer may shade differently).
std::string build_stamp() {
    std::string s = build_description();
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const auto t = std::filesystem::last_write_time(exe, ec);
        if (!ec) {
            const auto sys = std::chrono::file_clock::to_sys(t);
            s += ", executable time " +
                 std::to_string(
                     std::chrono::duration_cast<std::chrono::seconds>(sys.time_since_epoch())
                         .count());
        }
    }
    return s;
}

/// Progress on stderr: a rewritten line on a terminal, a line per phase otherwise.
struct Reporter {
    bool quiet = false, tty = false;
    void phase(const std::string& text) const {
        if (!quiet) std::fprintf(stderr, "report: %s\n", text.c_str());
    }
    void update(const std::string& text) const {
        if (!quiet && tty) std::fprintf(stderr, "\r\033[Kreport: %s", text.c_str());
    }
    void done() const {
        if (!quiet && tty) std::fprintf(stderr, "\r\033[K");
    }
};

/// ", T s, ~R s left": the time since `start` and, once some work is done, an estimate of the
/// time left from the pace so far.
std::string seconds_left(double start, int done, int total) {
    const double spent = now_seconds() - start;
    char buf[64];
    if (done <= 0)
        std::snprintf(buf, sizeof buf, ", %.0f s", spent);
    else
        std::snprintf(buf, sizeof buf, ", %.0f s, ~%.0f s left", spent,
                      spent / done * (total - done));
    return buf;
}

struct LoadedScene {
    std::string path, stem;
    SceneData scene;
    double load_ms = 0.0;
};

/// The first lines of a scene's report: the scene, the build and the setup times.
void print_scene_header(const LoadedScene& ls, int threads, double build_ms) {
    const int w = ls.scene.camera.width, h = ls.scene.camera.height;
    std::printf("report  scene=%s  %dx%d  threads=%d  isa=%s  W=%d\n", ls.path.c_str(), w, h,
                threads, isa_name(active_isa()), isa_width(active_isa()));
    std::printf("build   %s; %s\n", build_description().c_str(), cpu_model().c_str());
    std::printf("setup   load %.1f ms, BVH build %.1f ms (not in the times below)\n", ls.load_ms,
                build_ms);
}

/// The scene's analytic reference (error-vs-time.md, "Analytic references"), if it has one.
std::optional<Reference> analytic_scene_reference(const LoadedScene& ls, const Reporter& rep) {
    const double t_analytic = now_seconds();
    std::optional<AnalyticReference> a = analytic_reference(ls.scene);
    if (!a) return std::nullopt;
    Reference ref;
    ref.seconds = now_seconds() - t_analytic;
    rep.phase(ls.stem + ": analytic reference (" + a->name + ")");
    ref.film = std::move(a->film);
    ref.kind = "analytic: " + a->name;
    std::printf("ref     analytic (%s), no noise, %.1f s\n", a->name.c_str(), ref.seconds);
    return ref;
}

/// The converged reference: the cached one when its key matches (and --fresh-reference is off),
/// else rendered and saved to the cache.
Reference converged_scene_reference(const LoadedScene& ls, const Accel& accel,
                                    const ReportOptions& o, const ReferenceParams& rp,
                                    const Reporter& rep) {
    const int w = ls.scene.camera.width, h = ls.scene.camera.height;
    const std::string key = reference_cache_key(ls.path, w, h, rp);
    const std::string file =
        (std::filesystem::path(o.out_dir) / ("reference_" + ls.stem + "_" + key + ".pfm")).string();
    std::string cached_build;
    std::optional<Reference> cached;
    if (!o.fresh_reference) cached = load_reference(file, w, h, &cached_build);
    if (cached) {
        std::printf("ref     converged, %d spp, %s path, seeds 0x%08x+, reused from %s\n",
                    cached->spp, path_name(rp.path), rp.seed, file.c_str());
        if (cached_build != build_stamp())
            std::printf(
                "note    the cached reference was made by another build (%s); "
                "--fresh-reference renders it again\n",
                cached_build.c_str());
        return std::move(*cached);
    }
    const int chunk = std::clamp(rp.chunk_spp, 2, rp.spp / 2);
    rep.phase(ls.stem + ": rendering the reference, " + std::to_string(rp.spp) + " spp in " +
              std::to_string((rp.spp + chunk - 1) / chunk) + " chunks");
    const double start = now_seconds();
    Reference ref = render_converged_reference(ls.scene, accel, rp, [&](int done, int total) {
        rep.update(ls.stem + ": reference " + std::to_string(done) + "/" + std::to_string(total) +
                   " chunks" + seconds_left(start, done, total));
    });
    rep.done();
    std::filesystem::create_directories(o.out_dir);
    save_reference(file, ref, build_stamp());
    std::printf(
        "ref     converged, %d spp, %s path, seeds 0x%08x+, rendered in %.1f s, "
        "saved to %s\n",
        ref.spp, path_name(rp.path), rp.seed, ref.seconds, file.c_str());
    return ref;
}

/// The reference of the scene's sweep: analytic when the scene has one, else converged. `ok`
/// becomes false when a converged reference has NaN or Inf samples.
Reference scene_reference(const LoadedScene& ls, const Accel& accel, const ReportOptions& o,
                          int workers, const Reporter& rep, bool& ok) {
    ReferenceParams rp;
    rp.spp = o.reference_spp;
    rp.threads = workers;
    rp.path = o.reference_path == "scalar" ? RenderPath::scalar : RenderPath::packet;
    if (std::optional<Reference> analytic = analytic_scene_reference(ls, rep))
        return std::move(*analytic);
    Reference ref = converged_scene_reference(ls, accel, o, rp, rep);
    const double largest = *std::max_element(o.spp_list.begin(), o.spp_list.end());
    std::printf("        Var(ref) = %.3g per value (halves A/B: MSE(A,B)/4)%s\n", ref.variance,
                ref.spp < 100 * largest
                    ? "; below 100 x the largest sweep value, so it inflates the smallest "
                      "errors"
                    : "");
    if (ref.nan_samples > 0) {
        std::printf("error   the reference has %llu NaN/Inf samples\n",
                    static_cast<unsigned long long>(ref.nan_samples));
        ok = false;
    }
    return ref;
}

/// The sweep the options ask for: their paths and sample counts, the scene's knobs.
SweepParams scene_sweep_params(const ReportOptions& o, const SceneData& scene, int workers) {
    SweepParams sp;
    sp.paths.clear();
    for (const std::string& p : o.paths)
        sp.paths.push_back(p == "scalar" ? RenderPath::scalar : RenderPath::packet);
    sp.knobs = sweep_knobs(scene);
    sp.samples = o.spp_list;
    sp.repeats = o.repeats;
    sp.threads = workers;
    return sp;
}

/// run_sweep with progress on stderr.
std::vector<SweepPoint> run_scene_sweep(const LoadedScene& ls, const Accel& accel,
                                        const Film& reference, const SweepParams& sp,
                                        const Reporter& rep) {
    rep.phase(
        ls.stem + ": sweep, " +
        std::to_string(sp.paths.size() * sp.knobs.size() * sp.samples.size() * size_t(sp.repeats)) +
        " renders");
    const double sweep_start = now_seconds();
    const std::vector<SweepPoint> points =
        run_sweep(ls.scene, accel, reference, sp, [&](int done, int total, const SweepPoint& pt) {
            rep.update(ls.stem + ": sweep " + std::to_string(done + 1) + "/" +
                       std::to_string(total) + " (" + path_name(pt.path) + ", " +
                       knob_name(pt.knob) + " " + std::to_string(pt.samples) + ")" +
                       seconds_left(sweep_start, done, total));
        });
    rep.done();
    return points;
}

/// Renders one scene's report: the reference, the sweep, the table and fits, the CSV and the
/// plot. Returns false when a check failed (NaN/Inf, ray counts).
bool report_scene(const LoadedScene& ls, const ReportOptions& o, const Reporter& rep) {
    const double t_build = now_seconds();
    const Accel accel = build_accel(ls.scene, BuildParams{});
    const double build_ms = elapsed_ms(t_build);
    const int workers = worker_threads(o.threads);  // 0: all
    const int threads = workers > 0 ? workers : tbb::info::default_concurrency();
    bool ok = true;
    print_scene_header(ls, threads, build_ms);
    const Reference ref = scene_reference(ls, accel, o, workers, rep, ok);
    const SweepParams sp = scene_sweep_params(o, ls.scene, workers);
    const std::vector<SweepPoint> points = run_scene_sweep(ls, accel, ref.film, sp, rep);
    const Speedups speedups = speedups_of(points, sp);
    ok = print_sweep_table(stdout, points, sp, speedups) && ok;
    print_fits(stdout, points, sp);
    if (speedups.both) print_speedup_summary(stdout, points, speedups);
    const SweepLabel label{ls.stem, ls.scene.camera.width, ls.scene.camera.height, threads};
    std::filesystem::create_directories(o.out_dir);
    const std::string csv_path = (std::filesystem::path(o.out_dir) / (ls.stem + ".csv")).string();
    write_text_file(csv_path, sweep_csv(label, sp, ref, points, speedups));
    const std::string svg_path = (std::filesystem::path(o.out_dir) / (ls.stem + ".svg")).string();
    write_text_file(svg_path, loglog_svg(sweep_plot(label, sp, ref, points)));
    std::printf("csv     %s\nplot    %s\n\n", csv_path.c_str(), svg_path.c_str());
    std::fflush(stdout);
    return ok;
}

int run_report(ReportOptions o) {
    std::sort(o.spp_list.begin(), o.spp_list.end());
    o.spp_list.erase(std::unique(o.spp_list.begin(), o.spp_list.end()), o.spp_list.end());
    if (o.spp_list.empty()) throw InputError("--spp-list: no sample counts");
    std::set<std::string> seen;
    std::vector<std::string> paths;
    for (const std::string& p : o.paths)
        if (seen.insert(p).second) paths.push_back(p);
    o.paths = paths;
    if (o.reference_spp == 0) o.reference_spp = std::max(4, 100 * o.spp_list.back());
    std::error_code ec;
    std::filesystem::create_directories(o.out_dir, ec);
    if (ec || !std::filesystem::is_directory(o.out_dir))
        throw InputError("--out-dir: cannot create " + o.out_dir +
                         (ec ? ": " + ec.message() : std::string(": not a directory")));

    // load every scene first, so a bad one fails before any rendering
    std::vector<LoadedScene> scenes;
    std::set<std::string> stems;
    for (const std::string& path : o.scenes) {
        LoadedScene ls;
        ls.path = path;
        const double t = now_seconds();
        ls.scene = load_command_scene(path);
        ls.load_ms = elapsed_ms(t);
        apply_resolution(ls.scene.camera, o.width, o.height);
        ls.stem = std::filesystem::path(path).stem().string();
        for (int i = 2; !stems.insert(ls.stem).second; ++i)
            ls.stem = std::filesystem::path(path).stem().string() + "-" + std::to_string(i);
        scenes.push_back(std::move(ls));
    }
    Reporter rep;
    rep.quiet = o.quiet;
    rep.tty = stderr_is_terminal();
    bool ok = true;
    for (const LoadedScene& ls : scenes) ok = report_scene(ls, o, rep) && ok;
    if (!ok) std::fprintf(stderr, "raylane: report: checks failed (NaN/Inf or ray counts)\n");
    return ok ? 0 : 1;
}

}  // namespace

void add_report_command(CLI::App& app, int& exit_code) {
    auto o = std::make_shared<ReportOptions>();
    CLI::App* cmd = app.add_subcommand(
        "report",
        "error against run time: a converged reference (100 x the largest --spp-list samples), "
        "then both paths at each sample count, --repeats times. At the defaults a full-HD scene "
        "takes tens of minutes (the reference is cached in --out-dir); --width 320 --spp-list "
        "1,2,4,8 takes well under a minute");
    cmd->add_option("scenes", o->scenes, "scene JSON files or models (.obj, .ply)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--out-dir", o->out_dir,
                    "where references, CSV and SVG go (default out/report)");
    cmd->add_option("--reference-spp", o->reference_spp,
                    "samples of the converged reference (default 100 x the largest --spp-list)")
        ->check(whole_in(4, 1 << 24));
    cmd->add_option("--reference-path", o->reference_path,
                    "renderer of the reference: packet (default) or scalar")
        ->check(CLI::IsMember({"packet", "scalar"}));
    cmd->add_option("--spp-list", o->spp_list, "sample counts of the sweep (default 1,2,4,...,64)")
        ->delimiter(',')
        ->check(whole_in(1, 1 << 16));
    cmd->add_option("--paths", o->paths, "renderers to sweep (default packet,scalar)")
        ->delimiter(',')
        ->check(CLI::IsMember({"packet", "scalar"}));
    cmd->add_option("--repeats", o->repeats, "seeds per point; time = median (default 3)")
        ->check(whole_in(1, 100));
    add_threads_option(cmd, o->threads);
    cmd->add_option("--width", o->width, "image width (alone: keeps the aspect ratio)")
        ->check(whole_in(1, max_film_side));
    cmd->add_option("--height", o->height, "image height (alone: keeps the aspect ratio)")
        ->check(whole_in(1, max_film_side));
    cmd->add_flag("--fresh-reference", o->fresh_reference,
                  "render the reference even when a cached one matches");
    cmd->add_flag("-q,--quiet", o->quiet, "no progress on stderr");
    cmd->callback([o, &exit_code] { exit_code = run_report(*o); });
}

}  // namespace raylane
