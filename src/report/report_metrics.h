// report: the error metrics of an image against a reference, and the fits and interpolation
// on log-log curves of error against time (`raylane report`, error-vs-time.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "image/film.h"

namespace raylane {

// ---------------------------------------------------------------------------------------------
// Metrics (error-vs-time.md, "Definitions")

/// ε of relMSE = mean((x - r)^2 / (r^2 + ε)); printed with every result.
inline constexpr double relmse_epsilon = 1e-2;
/// ε of SMAPE = mean(|x - r| / (|x| + |r| + ε)), the [0, 1] convention (no factor 2).
inline constexpr double smape_epsilon = 1e-3;

/// Error of `image` against `reference`, in double over the linear values of all N pixels and
/// 3 channels (each mean divides by 3N). Non-finite values are counted and never skipped: one of
/// them makes the squared metrics non-finite.
struct ErrorMetrics {
    double mse = 0.0;
    double rmse = 0.0;
    double relmse = 0.0;
    double smape = 0.0;
    double mean = 0.0;      ///< mean of the image over pixels and channels (a shift is bias)
    double ref_mean = 0.0;  ///< the same for the reference
    uint64_t nan_values = 0, inf_values = 0;  ///< non-finite channel values in the image
    uint64_t bad_pixels = 0;                  ///< pixels with at least one of them
};

/// Throws std::invalid_argument when the films differ in size.
ErrorMetrics compute_error(const Film& image, const Film& reference,
                           double relmse_eps = relmse_epsilon);

// ---------------------------------------------------------------------------------------------
// Fits and interpolation on log-log curves (error-vs-time.md, "What it does": the summary)

/// log10 y = a + b log10 x, least squares; r2 = coefficient of determination (1 when the points
/// lie on the line; 1 also when all y are equal). n = points used: those with finite x, y > 0.
struct LineFit {
    double a = 0.0, b = 0.0, r2 = 0.0;
    size_t n = 0;
};
/// Fewer than two usable points, or all x equal: n as counted, a = b = r2 = NaN.
LineFit fit_loglog(std::span<const double> x, std::span<const double> y);

/// The median of the values (the mean of the middle two for an even count); 0 for none.
double median(std::vector<double> values);

/// The x at which a fitted line reaches y: 10^((log10 y - a) / b) (the time to reach an RMSE
/// from the fitted lines); nullopt when the fit is unusable (b NaN or 0) or y <= 0.
std::optional<double> x_at_fit(const LineFit& fit, double y);

/// The earliest time at which a curve reaches `error`: linear interpolation in (log t, log error)
/// on every pair of consecutive points (in the given order, normally increasing samples) whose
/// errors bracket it, and the smallest of those times. Segments flatter than `min_slope` (|d log
/// error / d log t|) are skipped when min_slope > 0: on a bias floor or in noise the time at an
/// error is ill-conditioned. `slack` >= 0 also offers a point's own time when `error` is within a
/// factor (1 + slack) of its error: two paths with the same estimator have the same errors up to
/// rounding, so one path's point can lie just outside the other's bracket. nullopt when nothing
/// applies.
std::optional<double> time_at_error(std::span<const double> times, std::span<const double> errors,
                                    double error, double slack = 0.0, double min_slope = 0.0);

}  // namespace raylane
