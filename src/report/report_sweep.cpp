// report: the sweep, its curves and the speed-up at equal error (report_sweep.h).
#include "report/report_sweep.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

namespace raylane {

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

bool has_area_lights(const SceneData& scene) {
    return std::any_of(scene.lights.begin(), scene.lights.end(),
                       [](const Light& l) { return l.is_area(); });
}

bool has_glossy_materials(const SceneData& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
        return m.model == SpecularModel::glossy_phong && m.k_s > 0.0f;
    });
}

std::vector<SweepKnob> sweep_knobs(const SceneData& scene) {
    std::vector<SweepKnob> knobs{SweepKnob::spp};
    if (has_area_lights(scene)) knobs.push_back(SweepKnob::light);
    if (has_glossy_materials(scene)) knobs.push_back(SweepKnob::glossy);
    return knobs;
}

RenderParams sweep_params(const SceneData& scene, SweepKnob knob, int samples, int threads,
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

std::vector<SweepPoint> run_sweep(const SceneData& scene, const Accel& accel, const Film& reference,
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
                    // same seed, same work in every path (error-vs-time.md, "What it does")
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
