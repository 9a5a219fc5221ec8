// report: a sweep as CSV (report_csv.h).
#include "report/report_csv.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "report/report_metrics.h"

namespace raylane {

std::string sweep_csv(const SweepLabel& label, const SweepParams& sweep, const Reference& ref,
                      const std::vector<SweepPoint>& points, const Speedups& speedups) {
    std::string csv =
        "scene,path,knob,samples,width,height,threads,repeats,seconds_median,seconds_min,"
        "seconds_max,mrays_per_s,primary_rays,shadow_rays,reflection_rays,refraction_rays,"
        "glossy_rays,rmse,rmse_se,mse,mse_minus_var_ref,"
        "relmse,relmse_se,relmse_eps,smape,smape_eps,mean,ref_mean,nan_inf_values,nan_samples,"
        "speedup_over_scalar,reference,reference_spp,var_ref\n";
    // the scene's name quoted (RFC 4180: a quote doubled), as a file name may hold , and "
    std::string csv_stem;
    for (const char c : label.scene) csv_stem += c == '"' ? std::string("\"\"") : std::string(1, c);
    for (const SweepPoint& pt : points) {
        double lo = INFINITY, hi = 0.0;
        for (const RenderStats& r : pt.runs)
            lo = std::min(lo, r.seconds), hi = std::max(hi, r.seconds);
        const RenderStats first = pt.runs.empty() ? RenderStats{} : pt.runs.front();
        std::string su;
        if (speedups.both && pt.path == RenderPath::packet)
            if (const auto v = speedups.of(pt)) su = std::to_string(*v);
        char line[1024];
        std::snprintf(
            line, sizeof line,
            "\"%s\",%s,%s,%d,%d,%d,%d,%d,%.6g,%.6g,%.6g,%.6g,%llu,%llu,%llu,%llu,%llu,%.6g,%."
            "3g,%.6g,%.6g,"
            "%.6g,%.3g,%g,%.6g,%g,%.6g,%.6g,%llu,%llu,%s,",
            csv_stem.c_str(), path_name(pt.path), knob_name(pt.knob), pt.samples, label.width,
            label.height, label.threads, sweep.repeats, pt.seconds_median, lo, hi,
            pt.mrays_per_second(), static_cast<unsigned long long>(first.primary_rays),
            static_cast<unsigned long long>(first.shadow_rays),
            static_cast<unsigned long long>(first.reflection_rays),
            static_cast<unsigned long long>(first.refraction_rays),
            static_cast<unsigned long long>(first.glossy_rays), pt.error.rmse, pt.rmse_se,
            pt.error.mse, pt.error.mse - ref.variance, pt.error.relmse, pt.relmse_se,
            relmse_epsilon, pt.error.smape, smape_epsilon, pt.error.mean, pt.error.ref_mean,
            static_cast<unsigned long long>(pt.error.nan_values + pt.error.inf_values),
            static_cast<unsigned long long>(pt.nan_samples()), su.c_str());
        csv += line;
        std::snprintf(line, sizeof line, "\"%s\",%d,%.6g\n", ref.kind.c_str(), ref.spp,
                      ref.variance);
        csv += line;
    }
    return csv;
}

}  // namespace raylane
