// report: error metrics, log-log fits and interpolation of the report (report_metrics.h).
#include "report/report_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace raylane {

namespace {
constexpr double nan_value = std::numeric_limits<double>::quiet_NaN();
}  // namespace

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

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

}  // namespace raylane
