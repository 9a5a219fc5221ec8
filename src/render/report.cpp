// render: error against run time: metrics, references, the sweep. Declared in render/report.h;
// used by app/report_command.cpp.
#include "render/report.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "image/pfm.h"
#include "io/model_path.h"
#include "io/read_file.h"
#include "render/camera_rays.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"

namespace raylane {

namespace {
constexpr double nan_value = std::numeric_limits<double>::quiet_NaN();
}  // namespace

// ---------------------------------------------------------------------------------------------
// Metrics

ErrorMetrics compute_error(const Film& image, const Film& reference, double relmse_eps) {
    if (image.width != reference.width || image.height != reference.height ||
        image.pixels.size() != reference.pixels.size())
        throw std::invalid_argument("compute_error: image and reference differ in size");
    ErrorMetrics m;
    double sum_sq = 0.0, sum_rel = 0.0, sum_smape = 0.0, sum_x = 0.0, sum_r = 0.0;
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        bool bad = false;
        for (int c = 0; c < 3; ++c) {
            const double x = image.pixels[i][c], r = reference.pixels[i][c];
            if (std::isnan(x)) ++m.nan_values, bad = true;
            if (std::isinf(x)) ++m.inf_values, bad = true;
            const double d = x - r;
            sum_sq += d * d;
            sum_rel += d * d / (r * r + relmse_eps);
            sum_smape += std::fabs(d) / (std::fabs(x) + std::fabs(r) + smape_epsilon);
            sum_x += x;
            sum_r += r;
        }
        m.bad_pixels += bad;
    }
    const double n = 3.0 * static_cast<double>(image.pixels.size());
    if (n > 0) {
        m.mse = sum_sq / n;
        m.relmse = sum_rel / n;
        m.smape = sum_smape / n;
        m.mean = sum_x / n;
        m.ref_mean = sum_r / n;
    }
    m.rmse = std::sqrt(m.mse);
    return m;
}

// ---------------------------------------------------------------------------------------------
// Fits and interpolation

LineFit fit_loglog(std::span<const double> x, std::span<const double> y) {
    LineFit fit;
    std::vector<double> lx, ly;
    for (size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
        if (!(x[i] > 0.0) || !(y[i] > 0.0) || !std::isfinite(x[i]) || !std::isfinite(y[i]))
            continue;
        lx.push_back(std::log10(x[i]));
        ly.push_back(std::log10(y[i]));
    }
    fit.n = lx.size();
    fit.a = fit.b = fit.r2 = nan_value;
    if (fit.n < 2) return fit;
    const double n = static_cast<double>(fit.n);
    double mx = 0.0, my = 0.0;
    for (size_t i = 0; i < fit.n; ++i) mx += lx[i], my += ly[i];
    mx /= n;
    my /= n;
    double sxx = 0.0, sxy = 0.0, syy = 0.0;
    for (size_t i = 0; i < fit.n; ++i) {
        sxx += (lx[i] - mx) * (lx[i] - mx);
        sxy += (lx[i] - mx) * (ly[i] - my);
        syy += (ly[i] - my) * (ly[i] - my);
    }
    if (!(sxx > 0.0)) return fit;
    fit.b = sxy / sxx;
    fit.a = my - fit.b * mx;
    double ss_res = 0.0;
    for (size_t i = 0; i < fit.n; ++i) {
        const double e = ly[i] - (fit.a + fit.b * lx[i]);
        ss_res += e * e;
    }
    fit.r2 = syy > 0.0 ? 1.0 - ss_res / syy : 1.0;
    return fit;
}

std::optional<double> x_at_fit(const LineFit& fit, double y) {
    if (!(y > 0.0) || !std::isfinite(fit.a) || !std::isfinite(fit.b) || fit.b == 0.0)
        return std::nullopt;
    const double x = std::pow(10.0, (std::log10(y) - fit.a) / fit.b);
    return std::isfinite(x) ? std::optional<double>(x) : std::nullopt;
}

namespace {

/// log-log interpolation (or extrapolation) of t at error e on the segment (t0, e0)-(t1, e1).
double segment_time(double t0, double e0, double t1, double e1, double e) {
    if (e0 == e1) return t0;
    const double f = (std::log(e) - std::log(e0)) / (std::log(e1) - std::log(e0));
    return std::exp(std::log(t0) + f * (std::log(t1) - std::log(t0)));
}

bool positive(double v) { return v > 0.0 && std::isfinite(v); }

}  // namespace

std::optional<double> time_at_error(std::span<const double> times, std::span<const double> errors,
                                    double error, double slack, double min_slope) {
    const size_t n = std::min(times.size(), errors.size());
    if (n == 0 || !positive(error)) return std::nullopt;
    for (size_t i = 0; i < n; ++i)
        if (!positive(times[i]) || !positive(errors[i])) return std::nullopt;
    std::optional<double> best;
    auto offer = [&](double t) {
        if (std::isfinite(t) && (!best || t < *best)) best = t;
    };
    for (size_t i = 0; i + 1 < n; ++i) {
        const double lo = std::min(errors[i], errors[i + 1]);
        const double hi = std::max(errors[i], errors[i + 1]);
        if (!(error >= lo && error <= hi)) continue;
        const double slope =
            std::log(errors[i + 1] / errors[i]) / std::log(times[i + 1] / times[i]);
        if (min_slope > 0.0 && !(std::fabs(slope) >= min_slope)) continue;  // flat, or t0 = t1
        offer(segment_time(times[i], errors[i], times[i + 1], errors[i + 1], error));
    }
    const double limit = std::log1p(std::max(0.0, slack));
    for (size_t i = 0; i < n; ++i)
        if (std::fabs(std::log(error / errors[i])) <= limit) offer(times[i]);
    return best;
}

// ---------------------------------------------------------------------------------------------
// References

const char* path_name(RenderPath path) { return path == RenderPath::packet ? "packet" : "scalar"; }

RenderResult render_with(RenderPath path, const Scene& scene, const Accel& accel,
                         const RenderParams& params) {
    return path == RenderPath::packet ? render_packet(scene, accel, params)
                                      : render_scalar(scene, accel, params);
}

Reference render_converged_reference(const Scene& scene, const Accel& accel,
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

using dvec3 = glm::dvec3;

/// The lit-sphere case: nullopt when the scene is not one.
std::optional<AnalyticReference> lit_sphere(const Scene& scene, int ss) {
    if (scene.objects.size() != 1 || scene.environment >= 0) return std::nullopt;
    const Object& obj = scene.objects[0];
    if (obj.kind != ShapeKind::sphere || obj.has_transform ||
        obj.material >= scene.materials.size())
        return std::nullopt;
    const Material& m = scene.materials[obj.material];
    if (m.model != SpecularModel::phong || m.texture >= 0 || m.reflection != 0.0f || m.refractive ||
        m.emissive() || m.normal_map >= 0 || m.env_map >= 0)
        return std::nullopt;
    const Camera& cam = scene.camera;
    const dvec3 centre(scene.spheres[obj.shape].center);
    const double radius = scene.spheres[obj.shape].radius;
    const CameraFrame f = make_camera_frame(cam);
    const dvec3 org(f.origin);
    if (!(glm::length(org - centre) > radius) || cam.lens_radius != 0.0f) return std::nullopt;
    for (const Light& l : scene.lights) {
        if (l.kind == LightKind::point && !(glm::length(dvec3(l.position) - centre) > radius))
            return std::nullopt;
        if (l.kind != LightKind::point && l.kind != LightKind::directional) return std::nullopt;
    }
    const dvec3 c_d(m.c_d), c_s(m.c_s), background(scene.background);

    // radiance along the unit direction d from the camera
    auto radiance = [&](const dvec3& d) -> dvec3 {
        const dvec3 oc = org - centre;
        const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - radius * radius;
        const double disc = b * b - c;
        if (disc < 0.0) return background;
        const double t = -b - std::sqrt(disc);  // camera outside: the near root
        if (!(t > 0.0)) return background;
        const dvec3 p = org + t * d;
        const dvec3 n = (p - centre) / radius;
        const dvec3 mirror = d - 2.0 * glm::dot(d, n) * n;
        dvec3 colour = double(m.k_a) * c_d;
        for (const Light& l : scene.lights) {
            dvec3 to_light;
            double factor;
            if (l.kind == LightKind::point) {
                to_light = dvec3(l.position) - p;
                const double d2 = glm::dot(to_light, to_light);
                factor = l.intensity / d2;
                to_light /= std::sqrt(d2);
            } else {
                to_light = dvec3(l.direction);
                factor = l.intensity;
            }
            const double cos_theta = glm::dot(n, to_light);
            if (!(cos_theta > 0.0)) continue;
            const dvec3 e = dvec3(l.color) * factor;
            colour += double(m.k_d) * cos_theta * e * c_d;
            const double cos_alpha = glm::dot(to_light, mirror);
            if (m.k_s > 0.0f && cos_alpha > 0.0)
                colour += double(m.k_s) * std::pow(cos_alpha, double(m.exponent)) * e * c_s;
        }
        return colour;
    };

    AnalyticReference out;
    out.name = "lit sphere, " + std::to_string(ss) + "x" + std::to_string(ss) +
               " supersampled per pixel in double";
    out.film = make_film(cam.width, cam.height);
    const double half_w = f.half_width, half_h = f.half_height;
    const dvec3 u(f.u), v(f.v), w(f.w);
    tbb::parallel_for(
        tbb::blocked_range<int>(0, cam.height), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y) {
                for (int x = 0; x < cam.width; ++x) {
                    dvec3 sum(0.0);
                    for (int j = 0; j < ss; ++j) {
                        for (int i = 0; i < ss; ++i) {
                            // camera_ray of render/camera_rays.h, in double
                            const double px = x + (i + 0.5) / ss, py = y + (j + 0.5) / ss;
                            const double sx = (2.0 * px / cam.width - 1.0) * half_w;
                            const double sy = (1.0 - 2.0 * py / cam.height) * half_h;
                            const dvec3 d = glm::normalize(w + sx * u + sy * v);
                            sum += radiance(d);
                        }
                    }
                    out.film.at(x, y) = vec3(sum / double(ss * ss));
                }
            }
        });
    return out;
}

bool is_convex(ShapeKind kind) {
    return kind == ShapeKind::sphere || kind == ShapeKind::box || kind == ShapeKind::cylinder;
}

/// The mirror furnace: nullopt when the scene is not one.
std::optional<AnalyticReference> mirror_furnace(const Scene& scene) {
    if (scene.objects.size() != 1 || scene.environment >= 0) return std::nullopt;
    const Object& obj = scene.objects[0];
    if (!is_convex(obj.kind) || obj.material >= scene.materials.size()) return std::nullopt;
    const Material& m = scene.materials[obj.material];
    const ShadingOptions& s = scene.shading;
    const bool fresnel = m.fresnel && s.fresnel;
    if (m.reflection != 1.0f || fresnel || m.c_s != vec3(1.0f) || m.k_a_after != 0.0f ||
        (m.texture >= 0 && m.texture_specular) || m.refractive || m.emissive() ||
        m.normal_map >= 0 || m.env_map >= 0 || !s.reflection || s.max_reflection_depth < 1 ||
        s.override_reflected)
        return std::nullopt;
    AnalyticReference out;
    out.name = "mirror furnace, every pixel = background";
    out.film = make_film(scene.camera.width, scene.camera.height);
    std::fill(out.film.pixels.begin(), out.film.pixels.end(), scene.background);
    return out;
}

}  // namespace

std::optional<AnalyticReference> analytic_reference(const Scene& scene, int supersampling) {
    if (auto r = lit_sphere(scene, std::max(1, supersampling))) return r;
    if (auto r = mirror_furnace(scene)) return r;
    return std::nullopt;
}

namespace {

struct Fnv64 {
    uint64_t h = 0xcbf29ce484222325ull;
    void bytes(const void* data, size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    }
    void text(const std::string& s) {
        const uint64_t n = s.size();
        bytes(&n, sizeof n);
        bytes(s.data(), s.size());
    }
    void number(int64_t v) { bytes(&v, sizeof v); }
};

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
    Fnv64 h;
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

// ---------------------------------------------------------------------------------------------
// The sweep

const char* knob_name(SweepKnob knob) {
    switch (knob) {
        case SweepKnob::spp:
            return "spp";
        case SweepKnob::light:
            return "light";
        case SweepKnob::glossy:
            return "glossy";
    }
    return "?";
}

bool has_area_lights(const Scene& scene) {
    return std::any_of(scene.lights.begin(), scene.lights.end(),
                       [](const Light& l) { return l.is_area(); });
}

bool has_glossy_materials(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
        return m.model == SpecularModel::glossy_phong && m.k_s > 0.0f;
    });
}

std::vector<SweepKnob> sweep_knobs(const Scene& scene) {
    std::vector<SweepKnob> knobs{SweepKnob::spp};
    if (has_area_lights(scene)) knobs.push_back(SweepKnob::light);
    if (has_glossy_materials(scene)) knobs.push_back(SweepKnob::glossy);
    return knobs;
}

RenderParams sweep_params(const Scene& scene, SweepKnob knob, int samples, int threads,
                          uint32_t seed) {
    RenderParams p;
    p.spp = std::max(1, scene.camera.spp);
    p.threads = threads;
    p.seed = seed;
    switch (knob) {
        case SweepKnob::spp:
            p.spp = samples;
            break;
        case SweepKnob::light:
            p.light_samples = samples;
            break;
        case SweepKnob::glossy:
            p.glossy_samples = samples;
            break;
    }
    return p;
}

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Mean and standard error of the mean.
std::pair<double, double> mean_se(const std::vector<double>& v) {
    const double n = static_cast<double>(v.size());
    if (v.empty()) return {0.0, 0.0};
    double mean = 0.0;
    for (double x : v) mean += x;
    mean /= n;
    if (std::all_of(v.begin(), v.end(), [&](double x) { return x == v[0]; })) return {v[0], 0.0};
    double ss = 0.0;
    for (double x : v) ss += (x - mean) * (x - mean);
    return {mean, std::sqrt(ss / (n - 1.0) / n)};
}

}  // namespace

double SweepPoint::mrays_per_second() const {
    std::vector<double> rates;
    for (const RenderStats& r : runs)
        if (r.seconds > 0.0)
            rates.push_back(static_cast<double>(r.total_rays()) / r.seconds * 1e-6);
    return median(rates);
}

uint64_t SweepPoint::nan_samples() const {
    uint64_t n = 0;
    for (const RenderStats& r : runs) n += r.bad_samples();
    return n;
}

std::vector<SweepPoint> run_sweep(const Scene& scene, const Accel& accel, const Film& reference,
                                  const SweepParams& params, const SweepProgress& progress) {
    const size_t nk = params.knobs.size(), np = params.paths.size(), ns = params.samples.size();
    const int repeats = std::max(1, params.repeats);
    if (static_cast<uint32_t>(repeats) >= reference_seed)
        throw std::invalid_argument("sweep: seeds would reach the reference's");
    std::vector<SweepPoint> points(nk * np * ns);
    std::vector<std::vector<ErrorMetrics>> errors(points.size());
    auto index = [&](size_t k, size_t p, size_t s) { return (k * np + p) * ns + s; };
    if (params.warm_up)
        for (RenderPath path : params.paths)
            (void)render_with(path, scene, accel,
                              sweep_params(scene, SweepKnob::spp, 1, params.threads, 1));
    const int total = static_cast<int>(points.size()) * repeats;
    int started = 0;
    for (size_t k = 0; k < nk; ++k) {
        for (size_t s = 0; s < ns; ++s) {
            for (int rep = 0; rep < repeats; ++rep) {
                for (size_t p = 0; p < np; ++p) {
                    SweepPoint& pt = points[index(k, p, s)];
                    pt.path = params.paths[p];
                    pt.knob = params.knobs[k];
                    pt.samples = params.samples[s];
                    if (progress) progress(started, total, pt);
                    ++started;
                    const RenderParams rp = sweep_params(scene, pt.knob, pt.samples, params.threads,
                                                         static_cast<uint32_t>(1 + rep));
                    const RenderResult r = render_with(pt.path, scene, accel, rp);
                    pt.runs.push_back(r.stats);
                    // the same work in every path at the same seed (error-vs-time.md 3.4, 2)
                    const RenderStats& first = points[index(k, 0, s)].runs.back();
                    if (r.stats.primary_rays != first.primary_rays ||
                        r.stats.shadow_rays != first.shadow_rays ||
                        r.stats.reflection_rays != first.reflection_rays ||
                        r.stats.refraction_rays != first.refraction_rays ||
                        r.stats.glossy_rays != first.glossy_rays)
                        pt.rays_match = false;
                    errors[index(k, p, s)].push_back(compute_error(r.film, reference));
                }
            }
        }
    }
    for (size_t i = 0; i < points.size(); ++i) {
        SweepPoint& pt = points[i];
        std::vector<double> seconds;
        for (const RenderStats& r : pt.runs) seconds.push_back(r.seconds);
        pt.seconds_median = median(seconds);
        std::vector<double> mse, rmse, relmse, smape, mean, ref_mean;
        for (const ErrorMetrics& e : errors[i]) {
            mse.push_back(e.mse);
            rmse.push_back(e.rmse);
            relmse.push_back(e.relmse);
            smape.push_back(e.smape);
            mean.push_back(e.mean);
            ref_mean.push_back(e.ref_mean);
            pt.error.nan_values += e.nan_values;
            pt.error.inf_values += e.inf_values;
            pt.error.bad_pixels += e.bad_pixels;
        }
        pt.error.mse = mean_se(mse).first;
        std::tie(pt.error.rmse, pt.rmse_se) = mean_se(rmse);
        std::tie(pt.error.relmse, pt.relmse_se) = mean_se(relmse);
        pt.error.smape = mean_se(smape).first;
        pt.error.mean = mean_se(mean).first;
        pt.error.ref_mean = mean_se(ref_mean).first;
    }
    return points;
}

Curve curve_of(std::span<const SweepPoint> points, RenderPath path, SweepKnob knob) {
    Curve c;
    for (const SweepPoint& p : points) {
        if (p.path != path || p.knob != knob) continue;
        c.samples.push_back(p.samples);
        c.seconds.push_back(p.seconds_median);
        c.rmse.push_back(p.error.rmse);
    }
    return c;
}

std::vector<std::optional<double>> speedup_at_equal_error(const Curve& slow, const Curve& fast,
                                                          double slack, double min_slope) {
    std::vector<std::optional<double>> out;
    for (size_t i = 0; i < fast.rmse.size(); ++i) {
        const std::optional<double> t =
            time_at_error(slow.seconds, slow.rmse, fast.rmse[i], slack, min_slope);
        if (t && fast.seconds[i] > 0.0)
            out.push_back(*t / fast.seconds[i]);
        else
            out.push_back(std::nullopt);
    }
    return out;
}

}  // namespace raylane
