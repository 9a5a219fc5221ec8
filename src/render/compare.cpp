// render: comparing the two paths.
#include "render/compare.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/camera_rays.h"
#include "traverse/intersect_packet.h"
#include "traverse/intersect_scalar.h"

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

size_t primary_id_mismatches(const Scene& scene, const Accel& accel) {
    constexpr int W = native_width;
    const Camera& cam = scene.camera;
    const CameraFrame frame = make_camera_frame(cam);
    return tbb::parallel_reduce(
        tbb::blocked_range<int>(0, cam.height), size_t(0),
        [&](const tbb::blocked_range<int>& rows, size_t bad) {
            for (int y = rows.begin(); y != rows.end(); ++y) {
                for (int x0 = 0; x0 < cam.width; x0 += W) {
                    RayPacket<W> p;
                    uint32_t b = 0;
                    for (int i = 0; i < W; ++i) {
                        Ray r = camera_ray(frame, float(std::min(x0 + i, cam.width - 1)) + 0.5f,
                                           float(y) + 0.5f);
                        if (x0 + i < cam.width) b |= 1u << i;
                        set_ray(p, i, r);
                    }
                    const vmask<W> active = mask_from_bits<W>(b);
                    const HitPacket<W> got = intersect_closest(scene, accel, p, active);
                    for_each_active(active, [&](int i) {
                        const Hit want = intersect_closest(scene, accel, get_ray(p, i));
                        const Hit g = get_hit(got, i);
                        bad += g.object != want.object || g.prim != want.prim;
                    });
                }
            }
            return bad;
        },
        [](size_t a, size_t b) { return a + b; });
}

}  // namespace raylane
