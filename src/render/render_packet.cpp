// render: the packet renderer's tile loop: tiles of camera packets, samples, sums, the film, and
// the kernel for the scene's features. Mirrors render_scalar.cpp. Shading a tile's samples:
// wavefront_packet.h; the analysis images: aov_packet.cpp.
#include "render/render_packet.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cstring>
#include <vector>

#include "core/rng.h"
#include "render/aov_packet.h"
#include "render/camera_rays_packet.h"
#include "render/sample_sum_packet.h"
#include "render/tiles.h"
#include "render/wavefront_packet.h"
#include "scene/features.h"
#include "shade/shade_packet.h"
#include "simd/hash.h"
#include "traverse/intersect_block.h"
#include "traverse/intersect_packet.h"

namespace raylane::RAYLANE_ISA_NS {
namespace {

/// A camera packet covers packet_cols x packet_rows pixels of its tile: 4x4 at W = 16, 4x2 at 8,
/// 2x2 at 4. A square's rays stay closer together through the BVH than a row's.
template <int W>
constexpr int packet_cols = W >= 8 ? 4 : (W >= 2 ? 2 : 1);
template <int W>
constexpr int packet_rows = W / packet_cols<W>;

/// A camera packet's lanes in its packet_cols x packet_rows block of pixels: column
/// lane % packet_cols, row lane / packet_cols.
template <int W>
struct PacketLanes {
    alignas(64) int32_t cols[W], rows[W];
    vint<W> col, row;
    vint<W> pixel_offset;  ///< each lane's pixel from the packet's first in the image
};

/// Offset of each lane's pixel from the packet's first in an array `stride` pixels wide.
template <int W>
vint<W> lane_offset(const PacketLanes<W>& lanes, int stride) {
    alignas(64) int32_t offset[W];
    for (int i = 0; i < W; ++i) offset[i] = lanes.rows[i] * stride + lanes.cols[i];
    return load<W>(offset);
}

template <int W>
PacketLanes<W> make_packet_lanes(int image_width) {
    PacketLanes<W> lanes;
    for (int i = 0; i < W; ++i)
        lanes.cols[i] = i % packet_cols<W>, lanes.rows[i] = i / packet_cols<W>;
    lanes.col = load<W>(lanes.cols);
    lanes.row = load<W>(lanes.rows);
    lanes.pixel_offset = lane_offset(lanes, image_width);
    return lanes;
}

/// A tile as camera packets of packet_cols x packet_rows pixels (4x4 at W = 16: compact ray
/// bundles); lanes past the tile's edges are inactive.
template <int W>
struct TilePackets {
    static constexpr int max_packets = max_block_rays / W;
    int count = 0;   ///< packets in use
    int tile_w = 0;  ///< the tile's width in pixels
    vmask<W> active[max_packets];
    vint<W> xi[max_packets], yi[max_packets];  ///< each lane's pixel in the image
    vint<W> pixel[max_packets];                ///< the same as an index, row by row
    vint<W> slot[max_packets];                 ///< its index in the tile, row by row
};

/// The tile's packets; with secondary rays also the wavefront's slot -> pixel map (b.pixel).
template <int W, uint32_t F>
TilePackets<W> tile_packets(const Tile& tile, int image_width, const PacketLanes<W>& lanes,
                            TileBuffers& b) {
    TilePackets<W> tp;
    tp.tile_w = tile.x1 - tile.x0;
    const vint<W> slot_offset = lane_offset(lanes, tp.tile_w);
    int count = 0;
    for (int y0 = tile.y0; y0 < tile.y1; y0 += packet_rows<W>) {
        for (int x0 = tile.x0; x0 < tile.x1; x0 += packet_cols<W>, ++count) {
            tp.xi[count] = vint<W>(x0) + lanes.col;
            tp.yi[count] = vint<W>(y0) + lanes.row;
            tp.active[count] =
                mask_and(lt(tp.xi[count], vint<W>(tile.x1)), lt(tp.yi[count], vint<W>(tile.y1)));
            tp.pixel[count] = vint<W>(y0 * image_width + x0) + lanes.pixel_offset;
            tp.slot[count] = vint<W>((y0 - tile.y0) * tp.tile_w + (x0 - tile.x0)) + slot_offset;
            if constexpr (has_secondary_rays<F>) {  // the wavefront's slot -> pixel map
                for_each_active(tp.active[count], [&](int i) {
                    b.pixel[get(tp.slot[count], i)] = get(tp.pixel[count], i);
                });
            }
        }
    }
    assert(count <= TilePackets<W>::max_packets);  // tiles are at most 16x16 pixels
    tp.count = count;
    return tp;
}

/// Camera packet p's rays for sample s; inactive lanes get t_max = -1.
template <int W, uint32_t F>
RayPacket<W> camera_packet(const CameraFrame& frame, int spp, uint32_t seed,
                           const TilePackets<W>& tp, int p, int s) {
    const vint<W> si(s), seeds(static_cast<int32_t>(seed));
    // sample position: the pixel centre, or stratified in the pixel
    vfloat<W> jx(0.5f), jy(0.5f);
    if (spp > 1) {
        stratified_square<W>(s, spp, random_float<W>(tp.pixel[p], si, vint<W>(dim_pixel_x), seeds),
                             random_float<W>(tp.pixel[p], si, vint<W>(dim_pixel_y), seeds), jx, jy);
    }
    vfloat<W> lu(0.5f), lv(0.5f);
    if constexpr ((F & feature_lens) != 0) {
        if (frame.lens_radius > 0.0f) {
            lu = random_float<W>(tp.pixel[p], si, vint<W>(dim_lens_u), seeds);
            lv = random_float<W>(tp.pixel[p], si, vint<W>(dim_lens_v), seeds);
        }
    }
    RayPacket<W> r = camera_ray<W>(frame, to_float(tp.xi[p]) + jx, to_float(tp.yi[p]) + jy, lu, lv);
    r.t_max = select(tp.active[p], r.t_max, vfloat<W>(-1.0f));
    return r;
}

/// The tile's sums of samples per pixel, and its counts of NaN and infinite samples.
template <int W>
struct TileSums {
    PixelSumPacket<W> sum[max_block_rays / W];
    uint64_t nans = 0, infs = 0;
};

/// Adds one sample's values to the pixels' sums (samples in order, so the same sums).
template <int W>
void add_values(const TilePackets<W>& tp, const Vec3<W>* value, TileSums<W>& sums) {
    for (int p = 0; p < tp.count; ++p) {
        vmask<W> nan, inf;
        sample_kinds<W>(value[p], nan, inf);
        add_sample<W>(sums.sum[p], value[p], mask_andnot(tp.active[p], mask_or(nan, inf)));
        sums.nans += static_cast<uint64_t>(count(mask_and(tp.active[p], nan)));
        sums.infs += static_cast<uint64_t>(count(mask_and(tp.active[p], inf)));
    }
}

/// Sample s of the tile's pixels without a wavefront: an AOV, or the colour of a scene without
/// secondary rays (shade_camera_block).
template <int W, uint32_t F>
void sample_values(const SceneData& scene, const Accel& accel, const RenderParams& params,
                   const ShadeParams& shade, const CameraFrame& frame, int spp,
                   const TilePackets<W>& tp, int s, Vec3<W>* value, ShadeCounts& counts) {
    RayPacket<W> rays[TilePackets<W>::max_packets];
    for (int p = 0; p < tp.count; ++p)
        rays[p] = camera_packet<W, F>(frame, spp, params.seed, tp, p, s);
    if (params.aov != Aov::color) {
        aov_values<W>(scene, accel, rays, tp.active, tp.count, params.aov, value);
    } else if constexpr (!has_secondary_rays<F>) {
        shade_camera_block<W, F>(scene, accel, shade, s, params.seed, rays, tp.active, tp.slot,
                                 tp.pixel, tp.count, value, counts);
    } else {
        assert(false);  // colour with secondary rays always goes by wavefronts (wavefront_values)
    }
}

/// Samples s0 .. s0 + n - 1 of the tile's pixels in one wavefront (colour with secondary rays):
/// the camera rays into the queue, a packet's n samples one after the other; then passes until
/// every path has ended; then each sample's values into the sums.
template <int W, uint32_t F>
void wavefront_values(const SceneData& scene, const Accel& accel, const RenderParams& params,
                      const ShadeParams& shade, const CameraFrame& frame, int spp,
                      const TilePackets<W>& tp, int s0, int n, TileBuffers& b, TileSums<W>& sums,
                      ShadeCounts& counts) {
    b.paths.clear();
    std::fill(b.acc_r, b.acc_r + n * max_block_rays, 0.0f);
    std::fill(b.acc_g, b.acc_g + n * max_block_rays, 0.0f);
    std::fill(b.acc_b, b.acc_b + n * max_block_rays, 0.0f);
    const Vec3<W> one = make_vec3<W>(1.0f, 1.0f, 1.0f);
    const vint<W> zero(0), none(-1);
    for (int p = 0; p < tp.count; ++p) {
        for (int j = 0; j < n; ++j) {
            const RayPacket<W> r = camera_packet<W, F>(frame, spp, params.seed, tp, p, s0 + j);
            push_packet<W>(b.paths, r.org, r.dir, one, one,
                           tp.slot[p] + vint<W>(j * max_block_rays), none, zero, zero, zero, none,
                           zero, tp.active[p]);
        }
    }
    shade_tile_samples<W, F>(scene, accel, shade, s0, params.seed, b, counts);
    Vec3<W> value[TilePackets<W>::max_packets];
    for (int j = 0; j < n; ++j) {
        for (int p = 0; p < tp.count; ++p) {
            const vint<W> at = tp.slot[p] + vint<W>(j * max_block_rays);
            value[p].x = gather(b.acc_r, at, tp.active[p]);
            value[p].y = gather(b.acc_g, at, tp.active[p]);
            value[p].z = gather(b.acc_b, at, tp.active[p]);
        }
        add_values<W>(tp, value, sums);
    }
}

/// The tile's pixel means into the film: into a buffer in film order (slot[p] holds each lane's
/// index in it), then into the film a row at a time: a few wide stores per row instead of three
/// per pixel.
template <int W>
void write_tile(const Tile& tile, const TilePackets<W>& tp, const TileSums<W>& sums,
                const PixelRect& region, Film& film) {
    static_assert(sizeof(vec3) == 3 * sizeof(float));  // runs of floats copied as pixels
    alignas(64) vec3 tile_rgb[max_block_rays];
    for (int p = 0; p < tp.count; ++p) {
        const Vec3<W> mean = pixel_mean<W>(sums.sum[p]);
        alignas(64) float rgb[3 * W];
        store_vec3_aos(rgb, mean);
        if (all(tp.active[p])) {  // inside the tile: a row of the packet is a run of the buffer
            const int at = get(tp.slot[p], 0);
            for (int r = 0; r < packet_rows<W>; ++r)
                std::memcpy(&tile_rgb[at + r * tp.tile_w], &rgb[3 * r * packet_cols<W>],
                            3 * packet_cols<W> * sizeof(float));
        } else {
            alignas(64) int32_t at[W];
            store_aligned(at, tp.slot[p]);
            for_each_active(tp.active[p], [&](int i) {
                tile_rgb[at[i]] = vec3(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]);
            });
        }
    }
    // the film holds the region: the tile's rows and columns inside it
    const int x0 = std::max(tile.x0, region.x0), x1 = std::min(tile.x1, region.x1);
    for (int y = std::max(tile.y0, region.y0); y < std::min(tile.y1, region.y1); ++y) {
        vec3* row = &film.at(x0 - region.x0, y - region.y0);
        const vec3* from = &tile_rgb[(y - tile.y0) * tp.tile_w + (x0 - tile.x0)];
        if (x1 - x0 == 16)  // the common case: a copy of constant size, inlined
            std::memcpy(row, from, 16 * sizeof(vec3));
        else
            std::memcpy(row, from, static_cast<size_t>(x1 - x0) * sizeof(vec3));
    }
}

template <int W, uint32_t F>
RenderResult render_packet_features(const SceneData& scene, const Accel& accel,
                                    const RenderParams& params) {
    const auto start = std::chrono::steady_clock::now();
    const Camera& cam = scene.camera;
    const CameraFrame frame = make_camera_frame(cam);
    RenderResult result;
    const PixelRect region = render_region(params, cam.width, cam.height);
    result.film = make_film_for_overwrite(region.width(), region.height());
    const int spp = params.spp > 0 ? params.spp : 1;
    // a tile is a block: at most max_block_rays pixels, rows a multiple of W wide
    const int tile_size = std::min(params.tile_size, 16);
    const std::vector<Tile> tiles = make_tiles(cam.width, cam.height, tile_size, region);
    PerThreadStats per_thread;
    Progress progress{params.progress_label, tiles.size(), params.progress && stderr_is_terminal()};
    const PacketLanes<W> lanes = make_packet_lanes<W>(cam.width);
    const ShadeParams shade{params.light_samples, params.glossy_samples};
    const int wavefront_samples = samples_per_wavefront(scene, shade);

    for_each_tile(tiles, params.threads, progress, [&](const Tile& tile) {
        thread_local TileBuffers b;
        const TilePackets<W> tp = tile_packets<W, F>(tile, cam.width, lanes, b);
        TileSums<W> sums;
        ShadeCounts counts;
        // colour with secondary rays: wavefronts of several samples each; else one sample at a
        // time
        const bool by_wavefronts = has_secondary_rays<F> && params.aov == Aov::color;
        const int step = by_wavefronts ? wavefront_samples : 1;
        for (int s0 = 0; s0 < spp; s0 += step) {
            if (by_wavefronts) {
                wavefront_values<W, F>(scene, accel, params, shade, frame, spp, tp, s0,
                                       std::min(step, spp - s0), b, sums, counts);
            } else {
                Vec3<W> value[TilePackets<W>::max_packets];
                sample_values<W, F>(scene, accel, params, shade, frame, spp, tp, s0, value, counts);
                add_values<W>(tp, value, sums);
            }
        }
        write_tile<W>(tile, tp, sums, region, result.film);
        per_thread.local().add_tile(counts, sums.nans, sums.infs);
    });

    result.stats.primary_rays = static_cast<uint64_t>(region.width()) *
                                static_cast<uint64_t>(region.height()) * static_cast<uint64_t>(spp);
    for (const RenderStats& sums : per_thread) result.stats.add_counts(sums);
    result.stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

/// The kernel feature set for a scene's feature mask (scene_features): groups of features, so 16
/// kernels cover every scene.
uint32_t kernel_features(uint32_t scene_mask) {
    uint32_t f = 0;
    if (scene_mask & feature_textures) f |= feature_textures;
    if (scene_mask & feature_area_lights) f |= feature_area_lights;
    if (scene_mask & group_secondary) f |= group_secondary;
    if (scene_mask & (feature_environment | feature_lens)) f |= feature_environment | feature_lens;
    return f;
}

#ifndef RAYLANE_SANITIZED
constexpr uint32_t group_camera = feature_environment | feature_lens;

/// Calls the kernel compiled for exactly the feature groups in f.
template <int W>
RenderResult dispatch(uint32_t f, const SceneData& scene, const Accel& accel,
                      const RenderParams& params) {
    constexpr uint32_t T = feature_textures, A = feature_area_lights, S = group_secondary,
                       C = group_camera;
    switch (f) {
#define RAYLANE_KERNEL(bits) \
    case (bits):             \
        return render_packet_features<W, (bits)>(scene, accel, params);
        RAYLANE_KERNEL(0)
        RAYLANE_KERNEL(T)
        RAYLANE_KERNEL(A)
        RAYLANE_KERNEL(T | A)
        RAYLANE_KERNEL(S)
        RAYLANE_KERNEL(S | T)
        RAYLANE_KERNEL(S | A)
        RAYLANE_KERNEL(S | T | A)
        RAYLANE_KERNEL(C)
        RAYLANE_KERNEL(C | T)
        RAYLANE_KERNEL(C | A)
        RAYLANE_KERNEL(C | T | A)
        RAYLANE_KERNEL(C | S)
        RAYLANE_KERNEL(C | S | T)
        RAYLANE_KERNEL(C | S | A)
#undef RAYLANE_KERNEL
        default:
            return render_packet_features<W, kernel_features_all>(scene, accel, params);
    }
}

#endif

}  // namespace

template <int W>
RenderResult render_packet_width(const SceneData& scene, const Accel& accel,
                                 const RenderParams& params) {
#ifdef RAYLANE_SANITIZED
    // sanitizer builds compile two kernels, 16 take too long to build there: the generic one and
    // the one for scenes that use no kernel feature, so that the one-pass shading
    // (shade_camera_block) runs under the sanitizers too; the release tests check that every
    // specialised kernel gives the generic kernel's image
    if constexpr (W == native_width) {
        if (!params.generic_kernel && kernel_features(scene_features(scene)) == 0)
            return render_packet_features<W, 0>(scene, accel, params);
    }
    return render_packet_features<W, kernel_features_all>(scene, accel, params);
#else
    if (params.generic_kernel || W != native_width)
        return render_packet_features<W, kernel_features_all>(scene, accel, params);
    return dispatch<W>(kernel_features(scene_features(scene)), scene, accel, params);
#endif
}

RenderResult render_packet_isa(const SceneData& scene, const Accel& accel,
                               const RenderParams& params) {
    return render_packet_width<native_width>(scene, accel, params);
}

// Instantiations: the widths of this instruction set (RAYLANE_FOR_EACH_WIDTH, simd/simd.h).
#define RAYLANE_INSTANTIATE(W)                                                   \
    template RenderResult render_packet_width<W>(const SceneData&, const Accel&, \
                                                 const RenderParams&);
RAYLANE_FOR_EACH_WIDTH(RAYLANE_INSTANTIATE)
#undef RAYLANE_INSTANTIATE

}  // namespace raylane::RAYLANE_ISA_NS
