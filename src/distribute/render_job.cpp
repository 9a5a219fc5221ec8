// distribute: a render job's frames, parts, file names and output (render_job.h).
#include "distribute/render_job.h"

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "core/error.h"
#include "core/isa.h"
#include "core/rng.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "render/tiles.h"
#include "report/warnings.h"
#include "scene/camera_path.h"
#include "scene/features.h"

namespace raylane {

PartResult render_part(RenderJob& job, int frame, const PixelRect& region) {
    job.scene.camera = camera_at_frame(job.still, job.scene.camera_path, frame);
    RenderParams params = job.params;
    params.seed = frame_seed(job.params.seed, frame);
    params.region = region;
    if (job.first_frame != job.last_frame) {  // the progress line names the frame
        job.progress_label = "frame " + std::to_string(frame);
        params.progress_label = job.progress_label.c_str();
    }
    PartResult part;
    for (Aov aov : job.aovs) {
        params.aov = aov;
        if (job.aovs.size() > 1 && job.first_frame == job.last_frame)
            params.progress_label = aov_name(aov);
        RenderResult r = job.scalar ? render_scalar(job.scene, job.accel, params)
                                    : render_packet(job.scene, job.accel, params);
        if (part.films.empty()) part.stats = r.stats;
        part.films.push_back({aov, std::move(r.film)});
    }
    return part;
}

namespace {

/// The conversion of a frame pattern: where it starts and ends, and its flags and width.
struct FrameConversion {
    size_t begin = std::string::npos, end = 0;
    bool zero_pad = false;
    int width = 0;
};

FrameConversion find_conversion(const std::string& pattern) {
    FrameConversion c;
    for (size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') continue;
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            ++i;
            continue;
        }
        size_t j = i + 1;
        const bool zero = j < pattern.size() && pattern[j] == '0';
        if (zero) ++j;
        int width = 0;
        while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) &&
               width < 100)
            width = width * 10 + (pattern[j++] - '0');
        if (j >= pattern.size() || pattern[j] != 'd' || width >= 100) {
            throw InputError(pattern +
                             ": a '%' in a file name starts the frame number: %d, %4d or %04d "
                             "(%% for a '%')");
        }
        if (c.begin != std::string::npos)
            throw InputError(pattern + ": more than one frame number in the file name");
        c = {i, j + 1, zero, width};
        i = j;
    }
    return c;
}

}  // namespace

bool has_frame_number(const std::string& pattern) {
    return find_conversion(pattern).begin != std::string::npos;
}

std::string frame_output(const std::string& pattern, int frame) {
    const FrameConversion c = find_conversion(pattern);
    std::string out;
    for (size_t i = 0; i < pattern.size(); ++i) {
        if (i == c.begin) {
            std::string number = std::to_string(frame);
            if (int(number.size()) < c.width)
                number.insert(0, size_t(c.width) - number.size(), c.zero_pad ? '0' : ' ');
            out += number;
            i = c.end - 1;
        } else {
            out += pattern[i];
            if (pattern[i] == '%') ++i;  // %% is one %
        }
    }
    return out;
}

int strict_exit_code(const RenderJob& job, const RenderStats& total) {
    if (!job.strict || total.bad_samples() == 0) return 0;
    std::fprintf(stderr, "raylane: %s: %llu NaN and %llu infinite samples (--strict)\n",
                 job.scene.source.c_str(), static_cast<unsigned long long>(total.nan_samples),
                 static_cast<unsigned long long>(total.inf_samples));
    return 3;
}

void parse_frames(const std::string& text, int frame_count, int& first, int& last) {
    auto number = [&](const std::string& s) {
        if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos)
            throw InputError("--frames: expected A..B, A or all (whole numbers >= 0), got '" +
                             text + "'");
        return std::atoi(s.c_str());
    };
    if (text == "all") {
        first = 0, last = frame_count - 1;
        return;
    }
    const size_t dots = text.find("..");
    first = number(text.substr(0, dots));
    last = dots == std::string::npos ? first : number(text.substr(dots + 2));
    if (last < first) throw InputError("--frames: " + text + " ends before it starts");
    // A..B past the end stops at the last frame: a job array of K frames a job need not work
    // out its last job's end; a first frame past the end is refused
    if (dots != std::string::npos && first < frame_count) last = std::min(last, frame_count - 1);
    if (last >= frame_count) {
        std::string why = "--frames: ";
        why.append(text).append(": the scene's animation has ").append(std::to_string(frame_count));
        why.append(frame_count == 1 ? " frame (0)" : " frames (0..")
            .append(frame_count == 1 ? "" : std::to_string(frame_count - 1) + ")");
        throw InputError(why);
    }
}

PixelRect parse_region(const std::vector<int>& crop, const std::string& tile, int width,
                       int height) {
    if (!crop.empty() && !tile.empty()) throw InputError("--crop and --tile: give one of them");
    if (!crop.empty()) {
        const PixelRect r{crop[0], crop[1], crop[2], crop[3]};
        if (r.x0 < 0 || r.y0 < 0 || r.x1 > width || r.y1 > height || r.empty()) {
            std::string why = "--crop ";
            for (int v : crop) why.append(std::to_string(v)).append(" ");
            why.append("is not a rectangle X0 Y0 X1 Y1 inside the ")
                .append(std::to_string(width))
                .append("x")
                .append(std::to_string(height))
                .append(" frame (0 <= X0 < X1 <= width, 0 <= Y0 < Y1 <= height)");
            throw InputError(why);
        }
        return r;
    }
    if (tile.empty()) return {};
    const size_t slash = tile.find('/');
    auto number = [&](const std::string& s) {
        if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos)
            throw InputError("--tile: expected I/N (part I of N, 0 <= I < N), got '" + tile + "'");
        return std::atoi(s.c_str());
    };
    if (slash == std::string::npos) number("");
    const int index = number(tile.substr(0, slash)), count = number(tile.substr(slash + 1));
    if (count < 1)
        throw InputError("--tile " + tile + ": N, the number of parts, must be at least 1");
    if (index >= count)
        throw InputError("--tile " + tile + ": I must be below N: a frame cut into " +
                         std::to_string(count) + " parts has parts 0 to " +
                         std::to_string(count - 1));
    try {
        return tile_part(width, height, RenderParams{}.tile_size, index, count);
    } catch (const std::invalid_argument& e) {
        throw InputError(std::string("--tile: ") + e.what());
    }
}

void write_frame(const RenderJob& job, int frame, std::vector<AovFilm> films,
                 const RenderStats& s) {
    const RenderParams& params = job.params;
    const std::string output = frame_output(job.output, frame);
    const Aov aov = films.at(0).aov;
    const bool colour = aov == Aov::color;
    const Camera& cam = job.still;
    const PixelRect whole{0, 0, cam.width, cam.height};
    const PixelRect region = job.region.empty() ? whole : job.region;
    const uint64_t samples = uint64_t(region.width()) * uint64_t(region.height()) *
                             uint64_t(params.spp > 0 ? params.spp : 1);
    // a part (--crop, --tile) may be all sky: only the whole frame says whether it is black
    const bool part = !job.region.empty() && !(job.region == whole);
    const std::vector<std::string> warnings =
        colour && !part ? render_warnings(films[0].film, s, samples) : std::vector<std::string>{};
    const bool exr = image_format(output) == ImageFormat::exr;
    // a PFM or EXR holds an AOV's raw values (scene units, counts); a PNG its mapping (`scale`)
    const bool raw = !colour && !exr && image_format(output) == ImageFormat::pfm;
    PartInfo info = job.info;
    set_part_setting(info, "frame", std::to_string(frame));
    std::string scale;
    if (exr && !job.region.empty()) {  // --crop or --tile: a part of the frame
        write_part(output, std::move(films), region.x0, region.y0, cam.width, cam.height, info);
    } else {
        OutputOptions out;
        out.tonemap = job.scene.tonemap;
        out.threads = params.threads;
        out.exr_float = job.exr_float;
        if (exr) out.attributes = frame_attributes(info);
        scale = write_render_output(output, std::move(films), out);
    }

    const double mrays = s.seconds > 0 ? double(s.total_rays()) / s.seconds * 1e-6 : 0.0;
    if (job.first_frame != job.last_frame) {  // one line a frame
        if (!job.quiet)
            std::printf("frame %-4d %s, %.1f ms, %.2f Mrays/s\n", frame, output.c_str(),
                        1000.0 * s.seconds, mrays);
        for (const std::string& w : warnings)
            std::printf("warning    frame %d: %s\n", frame, w.c_str());
        std::fflush(stdout);
        return;
    }
    if (!job.quiet) {
        std::printf("features   %s\n", feature_names(scene_features(job.scene)).c_str());
        if (job.bvh != "median") std::printf("bvh        %s\n", job.bvh.c_str());
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
        std::printf("time       load %.1f ms, build %.1f ms, render %.1f ms\n", job.load_ms,
                    job.build_ms, 1000.0 * s.seconds);
        std::printf("speed      %.2f Mrays/s\n", mrays);
        if (!scale.empty()) std::printf("scale      %s\n", scale.c_str());
        if (raw || (exr && job.aovs.size() == 1 && !colour))
            std::printf("values     raw %s (docs/scene-format.md, Outputs)\n", aov_name(aov));
    }
    if (s.bad_samples() > 0)
        std::printf("warning    %llu NaN and %llu infinite samples were left out of their pixels\n",
                    static_cast<unsigned long long>(s.nan_samples),
                    static_cast<unsigned long long>(s.inf_samples));
    for (const std::string& w : warnings) std::printf("warning    %s\n", w.c_str());
    if (!job.quiet) std::printf("image      %s\n", output.c_str());
    std::fflush(stdout);
}

/// What is being rendered, before the progress line.
void print_header(const RenderJob& job, int ranks) {
    if (job.quiet) return;
    const int threads =
        job.params.threads > 0 ? job.params.threads : tbb::info::default_concurrency();
    const Camera& cam = job.still;
    std::printf("scene      %s\n", job.scene.source.c_str());
    std::printf(
        "resolution %dx%d, %d spp, %s\n", cam.width, cam.height, job.params.spp,
        job.aovs.size() > 1 ? "color, normal, depth and bvh-cost" : aov_name(job.params.aov));
    if (!job.region.empty() && !(job.region == PixelRect{0, 0, cam.width, cam.height})) {
        const PixelRect& r = job.region;
        std::printf("part       x %d..%d, y %d..%d (%dx%d pixels)\n", r.x0, r.x1 - 1, r.y0,
                    r.y1 - 1, r.width(), r.height());
    }
    if (job.first_frame != job.last_frame || frame_count(job.scene.camera_path) > 1) {
        std::printf("frames     %d..%d of the animation's 0..%d\n", job.first_frame, job.last_frame,
                    frame_count(job.scene.camera_path) - 1);
    }
    const char* path = job.scalar ? "scalar" : "packet";
    if (ranks > 1 && job.scalar)
        std::printf("path       %s (W = 1), %d ranks x %d threads\n", path, ranks, threads);
    else if (ranks > 1)
        std::printf("path       %s (%s, W = %d), %d ranks x %d threads\n", path,
                    isa_name(active_isa()), isa_width(active_isa()), ranks, threads);
    else if (job.scalar)
        std::printf("path       scalar, %d threads\n", threads);
    else
        std::printf("path       packet (%s, W = %d), %d threads\n", isa_name(active_isa()),
                    isa_width(active_isa()), threads);
    std::fflush(stdout);
}

bool launched_by_mpi() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
        const char* v = std::getenv(name);
        if (v && std::atoi(v) > 1) return true;
    }
    return false;
}

int rank_from_environment() {
    for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK"}) {
        if (const char* v = std::getenv(name)) return std::atoi(v);
    }
    return 0;
}

}  // namespace raylane
