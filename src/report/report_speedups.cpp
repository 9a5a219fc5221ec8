// report: the packet path's speed-up over the scalar path in a sweep (report_speedups.h).
#include "report/report_speedups.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace raylane {

Spread spread_of(std::vector<double> values) {
    Spread s;
    std::erase_if(values, [](double x) { return !std::isfinite(x); });
    if (values.empty()) return s;
    std::sort(values.begin(), values.end());
    s.n = values.size();
    s.median = s.n % 2 ? values[s.n / 2] : 0.5 * (values[s.n / 2 - 1] + values[s.n / 2]);
    s.lo = values.front();
    s.hi = values.back();
    return s;
}

Speedups speedups_of(const std::vector<SweepPoint>& points, const SweepParams& sweep) {
    Speedups out;
    out.both = std::count(sweep.paths.begin(), sweep.paths.end(), RenderPath::packet) &&
               std::count(sweep.paths.begin(), sweep.paths.end(), RenderPath::scalar);
    if (!out.both) return out;
    for (SweepKnob k : sweep.knobs) {
        const Curve s = curve_of(points, RenderPath::scalar, k);
        const Curve p = curve_of(points, RenderPath::packet, k);
        const auto su = speedup_at_equal_error(s, p);
        for (size_t i = 0; i < p.samples.size(); ++i) {
            out.at_equal_rmse[{k, int(p.samples[i])}] = su[i];
            if (su[i]) out.speedups.push_back(*su[i]);
            if (p.seconds[i] > 0) out.time_ratios.push_back(s.seconds[i] / p.seconds[i]);
        }
        // efficiency 1 / (relMSE t) at equal samples, packet over scalar
        const auto sp_s = std::find_if(points.begin(), points.end(), [&](const SweepPoint& q) {
            return q.path == RenderPath::scalar && q.knob == k;
        });
        const auto sp_p = std::find_if(points.begin(), points.end(), [&](const SweepPoint& q) {
            return q.path == RenderPath::packet && q.knob == k;
        });
        for (size_t i = 0; i < p.samples.size(); ++i) {
            const SweepPoint& a = *(sp_s + std::ptrdiff_t(i));
            const SweepPoint& b = *(sp_p + std::ptrdiff_t(i));
            const double den = b.error.relmse * b.seconds_median;
            if (den > 0.0) out.efficiency_ratios.push_back(a.error.relmse * a.seconds_median / den);
        }
    }
    return out;
}

}  // namespace raylane
