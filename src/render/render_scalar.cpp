// render: the scalar reference renderer. Mirrored by render_packet.cpp.
#include "render/render_scalar.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/rng.h"
#include "render/camera_rays.h"
#include "render/sample_sum_scalar.h"
#include "render/tiles.h"
#include "shade/shade_scalar.h"
#include "traverse/intersect_scalar.h"
#include "traverse/surface_scalar.h"

namespace raylane {
namespace {

/// One sample's value for the requested output.
vec3 sample_value(const SceneData& scene, const Accel& accel, const Ray& ray,
                  const SampleIndex& index, const RenderParams& params, ShadeCounts& counts) {
    if (params.aov == Aov::color) {
        PathRay path;
        path.ray = ray;
        const ShadeParams shade{params.light_samples, params.glossy_samples};
        return trace_path(scene, accel, path, index, shade, counts).radiance;
    }
    TraversalStats stats;
    const Hit hit =
        intersect_closest(scene, accel, ray, params.aov == Aov::bvh_cost ? &stats : nullptr);
    switch (params.aov) {
        case Aov::color:
            return vec3(0.0f);
        case Aov::normal:
            return hit.hit() ? surface_at(scene, ray, hit).shading_normal : vec3(0.0f);
        case Aov::depth:
            return vec3(hit.hit() ? hit.t : 0.0f);
        case Aov::bvh_cost:
            return vec3(static_cast<float>(stats.nodes_visited));
    }
    return vec3(0.0f);
}

}  // namespace

RenderResult render_scalar(const SceneData& scene, const Accel& accel, const RenderParams& params) {
    const auto start = std::chrono::steady_clock::now();
    const Camera& cam = scene.camera;
    const CameraFrame frame = make_camera_frame(cam);
    RenderResult result;
    const PixelRect region = render_region(params, cam.width, cam.height);
    result.film = make_film_for_overwrite(region.width(), region.height());
    const int spp = params.spp > 0 ? params.spp : 1;
    const std::vector<Tile> tiles = make_tiles(cam.width, cam.height, params.tile_size, region);
    PerThreadStats per_thread;
    Progress progress{params.progress_label, tiles.size(), params.progress && stderr_is_terminal()};

    for_each_tile(tiles, params.threads, progress, [&](const Tile& tile) {
        ShadeCounts counts;
        uint64_t nans = 0, infs = 0;
        // a pixel's samples depend on the pixel alone: the tile's pixels inside the region
        for (int y = std::max(tile.y0, region.y0); y < std::min(tile.y1, region.y1); ++y) {
            for (int x = std::max(tile.x0, region.x0); x < std::min(tile.x1, region.x1); ++x) {
                const uint32_t pixel = static_cast<uint32_t>(y * cam.width + x);
                PixelSum sum;
                for (int s = 0; s < spp; ++s) {
                    // sample position: the pixel centre, or stratified in the pixel
                    const uint32_t si = static_cast<uint32_t>(s);
                    vec2 j(0.5f);
                    if (spp > 1) {
                        j = stratified_square(s, spp,
                                              random_float(pixel, si, dim_pixel_x, params.seed),
                                              random_float(pixel, si, dim_pixel_y, params.seed));
                    }
                    float lu = 0.5f, lv = 0.5f;
                    if (frame.lens_radius > 0.0f) {
                        lu = random_float(pixel, si, dim_lens_u, params.seed);
                        lv = random_float(pixel, si, dim_lens_v, params.seed);
                    }
                    const Ray ray = camera_ray(frame, static_cast<float>(x) + j.x,
                                               static_cast<float>(y) + j.y, lu, lv);
                    const SampleIndex index{pixel, si, params.seed};
                    const vec3 value = sample_value(scene, accel, ray, index, params, counts);
                    switch (sample_kind(value)) {
                        case SampleKind::finite:
                            add_sample(sum, value);
                            break;
                        case SampleKind::nan:
                            ++nans;
                            break;
                        case SampleKind::inf:
                            ++infs;
                            break;
                    }
                }
                result.film.at(x - region.x0, y - region.y0) = pixel_mean(sum);
            }
        }
        per_thread.local().add_tile(counts, nans, infs);
    });

    result.stats.primary_rays = static_cast<uint64_t>(region.width()) *
                                static_cast<uint64_t>(region.height()) * static_cast<uint64_t>(spp);
    for (const RenderStats& sums : per_thread) result.stats.add_counts(sums);
    result.stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace raylane
