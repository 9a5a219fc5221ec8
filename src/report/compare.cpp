// report: the difference of two films (compare.h).
#include "report/compare.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace raylane {

ImageDiff diff_images(const Film& a, const Film& b) {
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument("diff_images: films differ in size");
    ImageDiff d;
    double sum_abs = 0.0, sum_sq = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        double pixel_max = 0.0;
        for (int c = 0; c < 3; ++c) {
            double diff = std::fabs(double(a.pixels[i][c]) - double(b.pixels[i][c]));
            if (!std::isfinite(diff)) diff = INFINITY;
            pixel_max = std::max(pixel_max, diff);
            const double scale = std::max(
                {1.0, std::fabs(double(a.pixels[i][c])), std::fabs(double(b.pixels[i][c]))});
            d.max_rel = std::max(d.max_rel, std::isfinite(scale) ? diff / scale : INFINITY);
            sum_abs += diff;
            sum_sq += diff * diff;
        }
        d.max_abs = std::max(d.max_abs, pixel_max);
        d.pixels_over_8bit += pixel_max > 1.0 / 255.0;
    }
    const double n = 3.0 * static_cast<double>(a.pixels.size());
    d.mean_abs = n > 0 ? sum_abs / n : 0.0;
    const double mse = n > 0 ? sum_sq / n : 0.0;
    d.rmse = std::sqrt(mse);
    d.psnr_db = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : INFINITY;
    return d;
}

}  // namespace raylane
