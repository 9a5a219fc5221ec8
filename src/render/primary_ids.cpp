// render: primary-hit agreement of the two paths (render/primary_ids.h), compiled once per
// instruction set; render/dispatch.cpp calls the set in use.
#include "render/primary_ids.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>

#include "render/camera_rays.h"
#include "traverse/intersect_packet.h"
#include "traverse/intersect_scalar.h"

namespace raylane::RAYLANE_ISA_NS {

size_t primary_id_mismatches_isa(const SceneData& scene, const Accel& accel) {
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

}  // namespace raylane::RAYLANE_ISA_NS
