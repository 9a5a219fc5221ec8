// report: a sweep as text for the terminal (report_table.h).
#include "report/report_table.h"

#include <optional>
#include <string>

#include "report/report_metrics.h"

namespace raylane {
namespace {

std::string opt_ratio(const std::optional<double>& v) {
    if (!v) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2fx", *v);
    return buf;
}

}  // namespace

bool print_sweep_table(std::FILE* out, const std::vector<SweepPoint>& points,
                       const SweepParams& sweep, const Speedups& speedups) {
    bool ok = true;
    std::fprintf(out,
                 "metrics RMSE; relMSE eps=%.0e; SMAPE in [0,1] eps=%.0e; time = render only, "
                 "median of %d interleaved runs; errors = mean over seeds 1..%d (+-se)\n",
                 relmse_epsilon, smape_epsilon, sweep.repeats, sweep.repeats);
    std::fprintf(out, "\n%-7s %-6s %7s %9s %8s %10s %9s %10s %8s %4s %9s\n", "path", "knob",
                 "samples", "time[s]", "Mrays/s", "RMSE", "+-se", "relMSE", "SMAPE", "NaN",
                 "speed-up");
    for (const SweepPoint& pt : points) {
        const uint64_t bad = pt.error.nan_values + pt.error.inf_values + pt.nan_samples();
        std::string su;
        if (speedups.both && pt.path == RenderPath::packet) su = opt_ratio(speedups.of(pt));
        std::fprintf(out, "%-7s %-6s %7d %9.4f %8.2f %10.3e %9.1e %10.3e %8.5f %4llu %9s\n",
                     path_name(pt.path), knob_name(pt.knob), pt.samples, pt.seconds_median,
                     pt.mrays_per_second(), pt.error.rmse, pt.rmse_se, pt.error.relmse,
                     pt.error.smape, static_cast<unsigned long long>(bad), su.c_str());
        if (bad > 0) ok = false;
        if (!pt.rays_match) {
            std::fprintf(out, "error   %s %s %d: ray counts differ from %s at the same seed\n",
                         path_name(pt.path), knob_name(pt.knob), pt.samples,
                         path_name(sweep.paths[0]));
            ok = false;
        }
    }
    return ok;
}

void print_fits(std::FILE* out, const std::vector<SweepPoint>& points, const SweepParams& sweep) {
    std::fprintf(out, "\nfit log10(RMSE) = a + b log10(x), least squares over the points above:\n");
    for (SweepKnob k : sweep.knobs) {
        for (RenderPath p : sweep.paths) {
            const Curve c = curve_of(points, p, k);
            const LineFit ft = fit_loglog(c.seconds, c.rmse);
            const LineFit fn = fit_loglog(c.samples, c.rmse);
            std::fprintf(out,
                         "  %-6s %-6s against time: b = %6.3f R2 = %.4f   against samples: "
                         "b = %6.3f R2 = %.4f\n",
                         path_name(p), knob_name(k), ft.b, ft.r2, fn.b, fn.r2);
        }
    }
    std::fprintf(out,
                 "  (expected b = -0.5 for independent samples, steeper with stratification "
                 "(-0.75 over edges); 1 spp is the pixel centre, not a random sample)\n");
}

void print_speedup_summary(std::FILE* out, const std::vector<SweepPoint>& points,
                           const Speedups& speedups) {
    const Spread st = spread_of(speedups.time_ratios), ss = spread_of(speedups.speedups);
    const Spread se = spread_of(speedups.efficiency_ratios);
    std::fprintf(out,
                 "equal samples  time scalar/packet: median %.2fx (range %.2f-%.2f, %zu "
                 "points)\n",
                 st.median, st.lo, st.hi, st.n);
    if (ss.n > 0)
        std::fprintf(out,
                     "equal RMSE     speed-up packet over scalar (log-log interpolation): "
                     "median %.2fx (range %.2f-%.2f, %zu points)\n",
                     ss.median, ss.lo, ss.hi, ss.n);
    else
        std::fprintf(out, "equal RMSE     no packet point within the scalar curve's RMSE range\n");
    // time to an error X from the fitted lines (X = the packet curve's middle RMSE)
    const Curve cs = curve_of(points, RenderPath::scalar, SweepKnob::spp);
    const Curve cp = curve_of(points, RenderPath::packet, SweepKnob::spp);
    if (!cp.rmse.empty()) {
        const double x = cp.rmse[cp.rmse.size() / 2];
        const auto ts = x_at_fit(fit_loglog(cs.seconds, cs.rmse), x);
        const auto tp = x_at_fit(fit_loglog(cp.seconds, cp.rmse), x);
        if (ts && tp)
            std::fprintf(out,
                         "time to RMSE %.3g from the fits: scalar %.4f s, packet %.4f s -> "
                         "%.2fx\n",
                         x, *ts, *tp, *ts / *tp);
    }
    std::fprintf(out,
                 "efficiency     1/(relMSE t), packet over scalar at equal samples: median "
                 "%.2fx (range %.2f-%.2f)\n",
                 se.median, se.lo, se.hi);
}

}  // namespace raylane
