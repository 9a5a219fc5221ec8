// render: the packet renderer. Mirrors render_scalar.cpp.
#include "render/render_packet.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <vector>

#include "core/rng.h"
#include "render/camera_rays_packet.h"
#include "render/tiles.h"
#include "shade/shade_packet.h"
#include "simd/hash.h"
#include "traverse/intersect_packet.h"

namespace raylane {
namespace {

template <int W>
vmask<W> finite(const Vec3<W>& c) {
    const vfloat<W> zero(0.0f);
    return mask_and(mask_and(c.x - c.x == zero, c.y - c.y == zero), c.z - c.z == zero);
}

/// One sample's values for the requested output, for the active lanes.
template <int W>
Vec3<W> sample_value(const Scene& scene, const Accel& accel, const RayPacket<W>& rays,
                     vmask<W> active, Aov aov, ShadeCounts& counts) {
    vint<W> nodes(0);
    const HitPacket<W> hits =
        intersect_closest(scene, accel, rays, active, aov == Aov::bvh_cost ? &nodes : nullptr);
    const vmask<W> hit = mask_and(active, hits.t < vfloat<W>(infinity));
    const Vec3<W> background =
        make_vec3<W>(scene.background.x, scene.background.y, scene.background.z);
    const Vec3<W> black = make_vec3<W>(0.0f, 0.0f, 0.0f);
    switch (aov) {
        case Aov::color:
            if (none(hit)) return background;
            return select(hit, shade_hit(scene, accel, rays, hits, hit, counts), background);
        case Aov::normal:
            if (none(hit)) return black;
            return select(hit, surface_at(scene, rays, hits, hit).shading_normal, black);
        case Aov::depth: {
            const vfloat<W> t = select(hit, hits.t, vfloat<W>(0.0f));
            return {t, t, t};
        }
        case Aov::bvh_cost: {
            const vfloat<W> n = to_float(nodes);
            return {n, n, n};
        }
    }
    return black;
}

}  // namespace

template <int W>
RenderResult render_packet_width(const Scene& scene, const Accel& accel,
                                 const RenderParams& params) {
    const auto start = std::chrono::steady_clock::now();
    const Camera& cam = scene.camera;
    const CameraFrame frame = make_camera_frame(cam);
    RenderResult result;
    result.film = make_film(cam.width, cam.height);
    const int spp = params.spp > 0 ? params.spp : 1;
    const std::vector<Tile> tiles = make_tiles(cam.width, cam.height, params.tile_size);
    std::atomic<uint64_t> shadow_rays{0}, nan_samples{0};
    Progress progress{"render", tiles.size(), params.progress && stderr_is_terminal()};
    const vint<W> lane = lane_index<W>();

    for_each_tile(tiles, params.threads, progress, [&](const Tile& tile) {
        ShadeCounts counts;
        uint64_t nans = 0;
        for (int y = tile.y0; y < tile.y1; ++y) {
            for (int x0 = tile.x0; x0 < tile.x1; x0 += W) {
                // a row of up to W pixels; lanes past the tile's edge are inactive
                const vint<W> xi = vint<W>(x0) + lane;
                const int lanes = std::min(W, tile.x1 - x0);
                const vmask<W> active = mask_from_bits<W>((1u << lanes) - 1u);
                const vint<W> pixel = vint<W>(y * cam.width) + xi;
                Vec3<W> sum = make_vec3<W>(0.0f, 0.0f, 0.0f);
                vfloat<W> good(0.0f);
                for (int s = 0; s < spp; ++s) {
                    // sample position: the pixel centre, or jittered in the pixel
                    vfloat<W> jx(0.5f), jy(0.5f);
                    if (spp > 1) {
                        const vint<W> si(s), seed(static_cast<int32_t>(params.seed));
                        jx = random_float<W>(pixel, si, vint<W>(dim_pixel_x), seed);
                        jy = random_float<W>(pixel, si, vint<W>(dim_pixel_y), seed);
                    }
                    RayPacket<W> rays =
                        camera_ray<W>(frame, to_float(xi) + jx, vfloat<W>(float(y)) + jy);
                    rays.t_max = select(active, rays.t_max, vfloat<W>(-1.0f));
                    const Vec3<W> value =
                        sample_value<W>(scene, accel, rays, active, params.aov, counts);
                    const vmask<W> ok = mask_and(active, finite(value));
                    sum = select(ok, sum + value, sum);
                    good = select(ok, good + vfloat<W>(1.0f), good);
                    nans += static_cast<uint64_t>(count(mask_andnot(active, ok)));
                }
                const Vec3<W> mean = sum / select(good > vfloat<W>(0.0f), good, vfloat<W>(1.0f));
                for_each_active(active, [&](int i) {
                    result.film.at(x0 + i, y) =
                        vec3(get(mean.x, i), get(mean.y, i), get(mean.z, i));
                });
            }
        }
        shadow_rays += counts.shadow_rays;
        nan_samples += nans;
    });

    result.stats.primary_rays = static_cast<uint64_t>(cam.width) * cam.height * spp;
    result.stats.shadow_rays = shadow_rays;
    result.stats.nan_samples = nan_samples;
    result.stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

RenderResult render_packet(const Scene& scene, const Accel& accel, const RenderParams& params) {
    return render_packet_width<native_width>(scene, accel, params);
}

template RenderResult render_packet_width<1>(const Scene&, const Accel&, const RenderParams&);
#if XSIMD_WITH_SSE2
template RenderResult render_packet_width<4>(const Scene&, const Accel&, const RenderParams&);
#endif
#if XSIMD_WITH_AVX2
template RenderResult render_packet_width<8>(const Scene&, const Accel&, const RenderParams&);
#endif
#if XSIMD_WITH_AVX512F
template RenderResult render_packet_width<16>(const Scene&, const Accel&, const RenderParams&);
#endif

}  // namespace raylane
