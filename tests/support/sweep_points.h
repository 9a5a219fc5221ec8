// Test support: made-up sweeps for the tests of what the report makes of one
// (tests/report/report_{speedups,table,csv,plot}_test.cpp), without rendering.
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "report/report_sweep.h"

namespace raylane::test {

/// A point of `repeats` runs of `seconds` each, `rays` primary rays per run, and an RMSE of
/// `rmse` (relMSE rmse^2, MSE rmse^2).
inline SweepPoint made_up_point(RenderPath path, SweepKnob knob, int samples, double seconds,
                                double rmse, int repeats = 2, uint64_t rays = 1000) {
    SweepPoint pt;
    pt.path = path;
    pt.knob = knob;
    pt.samples = samples;
    for (int i = 0; i < repeats; ++i) {
        RenderStats r;
        r.seconds = seconds;
        r.primary_rays = rays;
        pt.runs.push_back(r);
    }
    pt.seconds_median = seconds;
    pt.error.rmse = rmse;
    pt.error.mse = rmse * rmse;
    pt.error.relmse = rmse * rmse;
    pt.rmse_se = rmse / 100;
    return pt;
}

/// A sweep of both paths over samples 1, 2, 4 per knob, in run_sweep's order (knob, path,
/// samples): the same RMSE 0.4 / sqrt(samples) on both, the packet path twice as fast (0.1 s
/// per sample against 0.2 s).
inline std::vector<SweepPoint> made_up_sweep(const SweepParams& sweep) {
    std::vector<SweepPoint> points;
    for (SweepKnob knob : sweep.knobs)
        for (RenderPath path : sweep.paths)
            for (int samples : sweep.samples)
                points.push_back(made_up_point(path, knob, samples,
                                               (path == RenderPath::packet ? 0.1 : 0.2) * samples,
                                               0.4 / std::sqrt(double(samples)), sweep.repeats));
    return points;
}

/// SweepParams of made_up_sweep: both paths, the given knobs, samples 1, 2, 4, 2 repeats.
inline SweepParams made_up_params(std::vector<SweepKnob> knobs = {SweepKnob::spp}) {
    SweepParams sweep;
    sweep.knobs = std::move(knobs);
    sweep.samples = {1, 2, 4};
    sweep.repeats = 2;
    return sweep;
}

}  // namespace raylane::test
