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

/// One sample's values for the requested output, for a block of packets (a tile).
template <int W>
void sample_values(const Scene& scene, const Accel& accel, const RayPacket<W>* rays,
                   const vmask<W>* active, int count, Aov aov, Vec3<W>* value,
                   ShadeCounts& counts) {
    constexpr int max_packets = max_block_rays / W;
    HitPacket<W> hits[max_packets];
    vmask<W> hit[max_packets];
    vint<W> nodes[max_packets];
    if (aov == Aov::bvh_cost) {
        for (int p = 0; p < count; ++p) {
            nodes[p] = vint<W>(0);
            hits[p] = intersect_closest(scene, accel, rays[p], active[p], &nodes[p]);
        }
    } else {
        intersect_closest_block(scene, accel, rays, active, hits, count);
    }
    for (int p = 0; p < count; ++p) hit[p] = mask_and(active[p], hits[p].t < vfloat<W>(infinity));
    const Vec3<W> background =
        make_vec3<W>(scene.background.x, scene.background.y, scene.background.z);
    const Vec3<W> black = make_vec3<W>(0.0f, 0.0f, 0.0f);
    switch (aov) {
        case Aov::color:
            shade_hit(scene, accel, rays, hits, hit, count, value, counts);
            for (int p = 0; p < count; ++p) value[p] = select(hit[p], value[p], background);
            return;
        case Aov::normal:
            for (int p = 0; p < count; ++p)
                value[p] =
                    any(hit[p])
                        ? select(hit[p], surface_at(scene, rays[p], hits[p], hit[p]).shading_normal,
                                 black)
                        : black;
            return;
        case Aov::depth:
            for (int p = 0; p < count; ++p) {
                const vfloat<W> t = select(hit[p], hits[p].t, vfloat<W>(0.0f));
                value[p] = {t, t, t};
            }
            return;
        case Aov::bvh_cost:
            for (int p = 0; p < count; ++p) {
                const vfloat<W> n = to_float(nodes[p]);
                value[p] = {n, n, n};
            }
            return;
    }
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
    // a tile is a block: at most max_block_rays pixels, rows a multiple of W wide
    const int tile_size = std::min(params.tile_size, 16);
    const std::vector<Tile> tiles = make_tiles(cam.width, cam.height, tile_size);
    std::atomic<uint64_t> shadow_rays{0}, nan_samples{0};
    Progress progress{"render", tiles.size(), params.progress && stderr_is_terminal()};
    const vint<W> lane = lane_index<W>();

    for_each_tile(tiles, params.threads, progress, [&](const Tile& tile) {
        // the tile as rows of packets of up to W pixels; lanes past its right edge are inactive
        constexpr int max_packets = max_block_rays / W;
        RayPacket<W> rays[max_packets];
        vmask<W> active[max_packets];
        vint<W> pixel[max_packets], xi[max_packets];
        Vec3<W> sum[max_packets], value[max_packets];
        vfloat<W> good[max_packets], yf[max_packets];
        int count = 0;
        for (int y = tile.y0; y < tile.y1; ++y) {
            for (int x0 = tile.x0; x0 < tile.x1; x0 += W, ++count) {
                const int lanes = std::min(W, tile.x1 - x0);
                active[count] = mask_from_bits<W>((1u << lanes) - 1u);
                xi[count] = vint<W>(x0) + lane;
                yf[count] = vfloat<W>(float(y));
                pixel[count] = vint<W>(y * cam.width) + xi[count];
                sum[count] = make_vec3<W>(0.0f, 0.0f, 0.0f);
                good[count] = vfloat<W>(0.0f);
            }
        }
        ShadeCounts counts;
        uint64_t nans = 0;
        for (int s = 0; s < spp; ++s) {
            for (int p = 0; p < count; ++p) {
                // sample position: the pixel centre, or jittered in the pixel
                vfloat<W> jx(0.5f), jy(0.5f);
                if (spp > 1) {
                    const vint<W> si(s), seed(static_cast<int32_t>(params.seed));
                    jx = random_float<W>(pixel[p], si, vint<W>(dim_pixel_x), seed);
                    jy = random_float<W>(pixel[p], si, vint<W>(dim_pixel_y), seed);
                }
                rays[p] = camera_ray<W>(frame, to_float(xi[p]) + jx, yf[p] + jy);
                rays[p].t_max = select(active[p], rays[p].t_max, vfloat<W>(-1.0f));
            }
            sample_values<W>(scene, accel, rays, active, count, params.aov, value, counts);
            for (int p = 0; p < count; ++p) {
                const vmask<W> ok = mask_and(active[p], finite(value[p]));
                sum[p] = select(ok, sum[p] + value[p], sum[p]);
                good[p] = select(ok, good[p] + vfloat<W>(1.0f), good[p]);
                nans += static_cast<uint64_t>(raylane::count(mask_andnot(active[p], ok)));
            }
        }
        for (int p = 0; p < count; ++p) {
            const Vec3<W> mean =
                sum[p] / select(good[p] > vfloat<W>(0.0f), good[p], vfloat<W>(1.0f));
            const int x0 = get(xi[p], 0), y = static_cast<int>(get(yf[p], 0));
            for_each_active(active[p], [&](int i) {
                result.film.at(x0 + i, y) = vec3(get(mean.x, i), get(mean.y, i), get(mean.z, i));
            });
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
