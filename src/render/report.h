// render: error against run time (`raylane report`, ../shared/docs/error-vs-time.md): error
// metrics, converged and analytic references, the sample sweep of both paths, slope fits and the
// speed-up at equal error. The command around it is app/report_command.cpp.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "accel/bvh.h"
#include "image/film.h"
#include "render/render_params.h"
#include "scene/scene.h"

namespace raylane {

// ---------------------------------------------------------------------------------------------
// Metrics (error-vs-time.md section 1)

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
// Fits and interpolation on log-log curves (error-vs-time.md section 3)

/// log10 y = a + b log10 x, least squares; r2 = coefficient of determination (1 when the points
/// lie on the line; 1 also when all y are equal). n = points used: those with finite x, y > 0.
struct LineFit {
    double a = 0.0, b = 0.0, r2 = 0.0;
    size_t n = 0;
};
/// Fewer than two usable points, or all x equal: n as counted, a = b = r2 = NaN.
LineFit fit_loglog(std::span<const double> x, std::span<const double> y);

/// The x at which a fitted line reaches y: 10^((log10 y - a) / b) (error-vs-time.md 3.3, "time
/// to reach error X"); nullopt when the fit is unusable (b NaN or 0) or y <= 0.
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

// ---------------------------------------------------------------------------------------------
// References (error-vs-time.md section 2)

enum class RenderPath : uint8_t { packet, scalar };
const char* path_name(RenderPath path);
RenderResult render_with(RenderPath path, const Scene& scene, const Accel& accel,
                         const RenderParams& params);

/// Seeds of converged references start here (chunk k uses reference_seed + k); sweeps use
/// seeds from 1 up, so the two never share samples.
inline constexpr uint32_t reference_seed = 0x52454600u;

struct ReferenceParams {
    int spp = 6400;      ///< total samples per pixel (>= 4)
    int chunk_spp = 64;  ///< samples per render call (>= 2: one sample is the pixel centre)
    int threads = 0;
    uint32_t seed = reference_seed;
    RenderPath path = RenderPath::packet;
};

struct Reference {
    Film film;
    std::string kind;       ///< "converged" or "analytic: <case>"
    int spp = 0;            ///< 0 for analytic references
    double variance = 0.0;  ///< Var(ref) per value, from the halves A and B; 0 when analytic
    uint64_t nan_samples = 0;
    double seconds = 0.0;  ///< time to render (or evaluate) it
};

/// Called after each chunk: (chunks done, chunks in all).
using ChunkProgress = std::function<void(int, int)>;

/// A converged reference: chunks of chunk_spp samples with seeds seed, seed + 1, ...; even
/// chunks form half A, odd chunks half B; the reference is their sample-weighted mean in double,
/// Var(ref) = MSE(A, B) / (N (1/n_A + 1/n_B)) (= MSE(A, B) / 4 for equal halves).
Reference render_converged_reference(const Scene& scene, const Accel& accel,
                                     const ReferenceParams& params,
                                     const ChunkProgress& progress = {});

/// Built-in analytic references (error-vs-time.md 2.1), tried in order:
///  * "lit sphere" (2.1.1): one untransformed sphere with a plain Phong material (no texture,
///    mirror, glass, emission or normal map), lit by point lights outside it and directional
///    lights, seen by a pinhole camera outside it, background colour elsewhere. Each pixel is the
///    mean over a supersampling x supersampling grid of its footprint, evaluated in double with the
///    formula of shade/shade_scalar.h: k_a c_d + sum k_d F c c_d cos(theta) + k_s F c c_s
///    max(cos(alpha), 0)^e. A convex sphere never shadows its own lit side.
///  * "mirror furnace" (the Whitted form of the furnace test, 2.1.2): one sphere whose material
///    is a perfect angle-independent mirror (reflection 1, fresnel off, c_s 1, k_d, k_s, k_a and
///    k_a_after 0), no lights, background colour only: every pixel equals the background.
/// The white-Lambertian furnace needs diffuse surfaces lit by the environment, which the Whitted
/// renderer does not compute; it has no entry. A new case is one more function in report.cpp.
struct AnalyticReference {
    std::string name;
    Film film;
};
std::optional<AnalyticReference> analytic_reference(const Scene& scene, int supersampling = 64);

/// Hex key of a converged reference on disk: FNV-1a 64 of the scene file's bytes, the path,
/// size and modification time of every file the scene names (any string value that is an
/// existing file in the model search path), width, height, reference spp, chunk size, seed and
/// renderer. Throws InputError when the scene file cannot be read.
std::string reference_cache_key(const std::string& scene_path, int width, int height,
                                const ReferenceParams& params);

/// Writes the reference as PFM (image/pfm.h) plus a "<path>.txt" sidecar (spp, Var(ref), NaN
/// samples, seconds, `build`). Throws std::runtime_error when the files cannot be written.
void save_reference(const std::string& pfm_path, const Reference& ref, const std::string& build);
/// Reads what save_reference wrote; nullopt when either file is missing, malformed or not
/// width x height (a cache miss, never an error). `build` receives the sidecar's build line.
std::optional<Reference> load_reference(const std::string& pfm_path, int width, int height,
                                        std::string* build = nullptr);

// ---------------------------------------------------------------------------------------------
// The sweep

/// The sample count a sweep varies; the others keep the scene's own values.
enum class SweepKnob : uint8_t { spp, light, glossy };
const char* knob_name(SweepKnob knob);

bool has_area_lights(const Scene& scene);
bool has_glossy_materials(const Scene& scene);
/// spp always; light when the scene has area lights; glossy when it has glossy Phong materials.
std::vector<SweepKnob> sweep_knobs(const Scene& scene);

/// Render parameters of one point: the knob set to `samples`; spp stays the camera's for the
/// light and glossy knobs (so their error flattens at that spp's anti-aliasing error).
RenderParams sweep_params(const Scene& scene, SweepKnob knob, int samples, int threads,
                          uint32_t seed);

struct SweepParams {
    std::vector<RenderPath> paths{RenderPath::packet, RenderPath::scalar};
    std::vector<SweepKnob> knobs{SweepKnob::spp};
    std::vector<int> samples{1, 2, 4, 8, 16, 32, 64};
    int repeats = 3;  ///< seeds 1 .. repeats; time = median, errors = mean over them
    int threads = 0;
    bool warm_up = true;  ///< one untimed 1-spp render per path first
};

/// One (path, knob, samples) point: `repeats` renders with seeds 1, 2, ..., interleaved with the
/// other paths at the same seed (ABAB...).
struct SweepPoint {
    RenderPath path = RenderPath::packet;
    SweepKnob knob = SweepKnob::spp;
    int samples = 0;
    std::vector<RenderStats> runs;          ///< per repeat: render time, rays, NaN samples
    double seconds_median = 0.0;            ///< median render time over the repeats
    ErrorMetrics error;                     ///< mean over the repeats (non-finite counts summed)
    double rmse_se = 0.0, relmse_se = 0.0;  ///< standard error of those means
    /// Every repeat traced as many rays of each type as the first path at the same seed.
    bool rays_match = true;
    double mrays_per_second() const;  ///< median over the repeats of rays / render time
    uint64_t nan_samples() const;     ///< over all repeats
};

/// Called before each render: (renders started, renders in all, the point being rendered).
using SweepProgress = std::function<void(int, int, const SweepPoint&)>;

/// Runs the sweep against `reference`; points are ordered by knob, then path, then samples.
std::vector<SweepPoint> run_sweep(const Scene& scene, const Accel& accel, const Film& reference,
                                  const SweepParams& params, const SweepProgress& progress = {});

/// Times and RMSE of the points of one (path, knob), in sample order.
struct Curve {
    std::vector<double> samples, seconds, rmse;
};
Curve curve_of(std::span<const SweepPoint> points, RenderPath path, SweepKnob knob);

/// Speed-up of `fast` over `slow` at each of fast's points: t_slow(RMSE) / t_fast, t_slow by
/// time_at_error with `slack` and `min_slope`; nullopt where that RMSE is outside slow's range
/// or only on its flat parts. The default slack (0.1 %) covers the rounding differences of two
/// paths with the same estimator and no more.
std::vector<std::optional<double>> speedup_at_equal_error(const Curve& slow, const Curve& fast,
                                                          double slack = 1e-3,
                                                          double min_slope = 0.1);

}  // namespace raylane
