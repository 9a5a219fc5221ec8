// report: the difference of two films channel by channel, for `raylane compare` and the tests
// that compare the two paths' images. Tested by tests/report/compare_test.cpp.
#pragma once

#include <cstddef>

#include "image/film.h"

namespace raylane {

/// Per-channel differences of two films of the same size (linear values; NaN counts as a
/// difference of infinity).
struct ImageDiff {
    double max_abs = 0.0;
    double max_rel = 0.0;  ///< max |a - b| / max(1, |a|, |b|): rounding at any brightness
    double mean_abs = 0.0;
    double rmse = 0.0;
    double psnr_db = 0.0;         ///< 10 log10(1 / MSE), peak 1; +inf when identical
    size_t pixels_over_8bit = 0;  ///< pixels with a channel differing by more than 1/255
};
ImageDiff diff_images(const Film& a, const Film& b);

}  // namespace raylane
