// report: the report's converged references and their cache on disk (report_cache.h).
#include "report/report_cache.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "core/fnv1a.h"
#include "image/pfm.h"
#include "io/model_path.h"
#include "io/read_file.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"

namespace raylane {

const char* path_name(RenderPath path) { return path == RenderPath::packet ? "packet" : "scalar"; }

RenderResult render_with(RenderPath path, const SceneData& scene, const Accel& accel,
                         const RenderParams& params) {
    return path == RenderPath::packet ? render_packet(scene, accel, params)
                                      : render_scalar(scene, accel, params);
}

Reference render_converged_reference(const SceneData& scene, const Accel& accel,
                                     const ReferenceParams& params, const ChunkProgress& progress) {
    if (params.spp < 4) throw std::invalid_argument("reference: fewer than 4 samples per pixel");
    // two chunks at least (the halves), each of >= 2 samples (1 sample is the pixel centre)
    const int chunk = std::clamp(params.chunk_spp, 2, params.spp / 2);
    const int chunks = (params.spp + chunk - 1) / chunk;
    const size_t n_pix = static_cast<size_t>(scene.camera.width) * scene.camera.height;
    std::vector<double> sum[2] = {std::vector<double>(3 * n_pix, 0.0),
                                  std::vector<double>(3 * n_pix, 0.0)};
    double samples[2] = {0.0, 0.0};
    Reference ref;
    ref.kind = "converged";
    ref.spp = params.spp;
    for (int k = 0; k < chunks; ++k) {
        RenderParams p;
        p.spp = std::min(chunk, params.spp - k * chunk);
        if (p.spp == 1) p.spp = 2;  // a last chunk of one would be the pixel centre
        p.threads = params.threads;
        p.seed = params.seed + static_cast<uint32_t>(k);
        const RenderResult r = render_with(params.path, scene, accel, p);
        const int half = k % 2;
        for (size_t i = 0; i < n_pix; ++i)
            for (int c = 0; c < 3; ++c)
                sum[half][3 * i + static_cast<size_t>(c)] += double(r.film.pixels[i][c]) * p.spp;
        samples[half] += p.spp;
        ref.nan_samples += r.stats.bad_samples();
        ref.seconds += r.stats.seconds;
        if (progress) progress(k + 1, chunks);
    }
    ref.spp = static_cast<int>(samples[0] + samples[1]);
    ref.film = make_film(scene.camera.width, scene.camera.height);
    double sq = 0.0;
    for (size_t i = 0; i < n_pix; ++i) {
        for (int c = 0; c < 3; ++c) {
            const size_t j = 3 * i + static_cast<size_t>(c);
            const double a = sum[0][j] / samples[0], b = sum[1][j] / samples[1];
            sq += (a - b) * (a - b);
            ref.film.pixels[i][c] =
                static_cast<float>((sum[0][j] + sum[1][j]) / (samples[0] + samples[1]));
        }
    }
    const double mse_ab = n_pix > 0 ? sq / (3.0 * static_cast<double>(n_pix)) : 0.0;
    ref.variance = mse_ab / (ref.spp * (1.0 / samples[0] + 1.0 / samples[1]));
    return ref;
}

namespace {

/// Every string value in the JSON tree, depth-first.
void collect_strings(const nlohmann::json& j, std::vector<std::string>& out) {
    if (j.is_string())
        out.push_back(j.get<std::string>());
    else if (j.is_array() || j.is_object())
        for (const auto& item : j) collect_strings(item, out);
}

}  // namespace

std::string reference_cache_key(const std::string& scene_path, int width, int height,
                                const ReferenceParams& params) {
    const std::string text = read_file(scene_path);
    Fnv1a h;
    h.text("raylane reference v1");
    h.text(text);
    // files the scene names: mesh, texture and map names are string values that resolve
    std::vector<std::string> strings;
    const nlohmann::json json = nlohmann::json::parse(text, nullptr, false, true);
    if (!json.is_discarded()) collect_strings(json, strings);
    const std::string dir = std::filesystem::path(scene_path).parent_path().string();
    for (const std::string& s : strings) {
        if (s.empty() || s.size() > 4096 || s.find('.') == std::string::npos) continue;
        std::string found;
        try {
            found = find_model(s, dir);
        } catch (const InputError&) {
            continue;
        }
        std::error_code ec;
        const auto size = std::filesystem::file_size(found, ec);
        if (ec) continue;
        const auto mtime = std::filesystem::last_write_time(found, ec);
        if (ec) continue;
        h.text(found);
        h.number(static_cast<int64_t>(size));
        h.number(static_cast<int64_t>(mtime.time_since_epoch().count()));
    }
    for (int64_t v : {int64_t{width}, int64_t{height}, int64_t{params.spp},
                      int64_t{params.chunk_spp}, int64_t{params.seed}})
        h.number(v);
    h.text(path_name(params.path));
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.h));
    return hex;
}

void save_reference(const std::string& pfm_path, const Reference& ref, const std::string& build) {
    write_pfm(pfm_path, ref.film);
    const std::string meta = pfm_path + ".txt", tmp = meta + ".partial";
    {
        std::ofstream f(tmp);
        char line[128];
        f << "raylane reference v1\n";
        f << "kind " << ref.kind << "\n";
        f << "spp " << ref.spp << "\n";
        std::snprintf(line, sizeof line, "variance %.17g\n", ref.variance);
        f << line;
        f << "nan_samples " << ref.nan_samples << "\n";
        std::snprintf(line, sizeof line, "seconds %.6f\n", ref.seconds);
        f << line;
        f << "build " << build << "\n";
        if (!f) throw std::runtime_error(meta + ": cannot write");
    }
    std::error_code ec;
    std::filesystem::rename(tmp, meta, ec);
    if (ec) throw std::runtime_error(meta + ": cannot write: " + ec.message());
}

std::optional<Reference> load_reference(const std::string& pfm_path, int width, int height,
                                        std::string* build) {
    std::ifstream meta(pfm_path + ".txt");
    std::string line;
    if (!std::getline(meta, line) || line != "raylane reference v1") return std::nullopt;
    Reference ref;
    bool have_spp = false, have_var = false;
    while (std::getline(meta, line)) {
        const size_t space = line.find(' ');
        if (space == std::string::npos) continue;
        const std::string key = line.substr(0, space), value = line.substr(space + 1);
        std::istringstream in(value);
        if (key == "kind") ref.kind = value;
        if (key == "spp") have_spp = static_cast<bool>(in >> ref.spp);
        if (key == "variance") have_var = static_cast<bool>(in >> ref.variance);
        if (key == "nan_samples") in >> ref.nan_samples;
        if (key == "seconds") in >> ref.seconds;
        if (key == "build" && build) *build = value;
    }
    if (!have_spp || !have_var || ref.spp <= 0) return std::nullopt;
    std::optional<Film> film = read_pfm(pfm_path, width, height);
    if (!film) return std::nullopt;
    ref.film = std::move(*film);
    return ref;
}

}  // namespace raylane
