// report: the packet path's speed-up over the scalar path in a sweep: at equal RMSE point by
// point, and the time and efficiency ratios at equal samples, with their spread.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "report/report_sweep.h"

namespace raylane {

/// Median, min and max of the finite values of a list; n = how many there were.
struct Spread {
    double median = 0, lo = 0, hi = 0;
    size_t n = 0;
};
Spread spread_of(std::vector<double> values);

/// Packet over scalar, when the sweep has both paths: the speed-up at equal RMSE of each packet
/// point, and the ratios whose spread the summary lines give.
struct Speedups {
    bool both = false;  ///< both paths were swept (else everything below is empty)
    std::map<std::pair<SweepKnob, int>, std::optional<double>> at_equal_rmse;  ///< (knob, samples)
    std::vector<double> speedups, time_ratios, efficiency_ratios;
    /// The speed-up at equal RMSE of a packet point; nullopt when there is none.
    std::optional<double> of(const SweepPoint& pt) const {
        const auto it = at_equal_rmse.find({pt.knob, pt.samples});
        return it == at_equal_rmse.end() ? std::nullopt : it->second;
    }
};

/// The speed-ups of a sweep's points (run_sweep's order). Per knob: the speed-up at equal RMSE
/// (speedup_at_equal_error), the time ratio scalar / packet at equal samples, and the efficiency
/// ratio 1/(relMSE t) packet over scalar at equal samples.
Speedups speedups_of(const std::vector<SweepPoint>& points, const SweepParams& sweep);

}  // namespace raylane
