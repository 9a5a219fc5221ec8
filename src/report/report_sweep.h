// report: the sweep: renders of both paths over sample counts against a reference,
// their errors and times, and the speed-up of one path over the other at equal error.
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
#include "report/report_cache.h"
#include "report/report_metrics.h"
#include "scene/scene.h"

namespace raylane {

/// The sample count a sweep varies; the others keep the scene's own values.
enum class SweepKnob : uint8_t { spp, light, glossy };
const char* knob_name(SweepKnob knob);

bool has_area_lights(const SceneData& scene);
bool has_glossy_materials(const SceneData& scene);
/// spp always; light when the scene has area lights; glossy when it has glossy Phong materials.
std::vector<SweepKnob> sweep_knobs(const SceneData& scene);

/// Render parameters of one point: the knob set to `samples`; spp stays the camera's for the
/// light and glossy knobs (so their error flattens at that spp's anti-aliasing error).
RenderParams sweep_params(const SceneData& scene, SweepKnob knob, int samples, int threads,
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

/// What a sweep's CSV rows and plot title name it by: the scene (its file's stem), the image
/// size and the threads the renders ran on.
struct SweepLabel {
    std::string scene;
    int width = 0, height = 0, threads = 0;
};

/// Called before each render: (renders started, renders in all, the point being rendered).
using SweepProgress = std::function<void(int, int, const SweepPoint&)>;

/// Runs the sweep against `reference`; points are ordered by knob, then path, then samples.
std::vector<SweepPoint> run_sweep(const SceneData& scene, const Accel& accel, const Film& reference,
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
