// render: the options and results both renderers share.
#pragma once

#include <cstdint>
#include <string>

#include "image/film.h"
#include "shade/shade_scalar.h"

namespace raylane {

/// What a pixel shows. `color` is the shaded image; the others are the AOVs of --aov.
enum class Aov : uint8_t { color, normal, depth, bvh_cost };

/// Parses "color", "normal", "depth", "bvh-cost"; false when unknown.
bool parse_aov(const std::string& name, Aov& aov);
const char* aov_name(Aov aov);

/// Pixels [x0, x1) x [y0, y1) of a frame, row 0 at the top: a tile of the renderer's grid, or the
/// part of a frame a render covers.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    bool operator==(const PixelRect&) const = default;
};

struct RenderParams {
    int spp = 1;      ///< samples per pixel: 1 = pixel centre, more = jittered in the pixel
    int threads = 0;  ///< 0 = all hardware threads
    uint32_t seed = 0;
    Aov aov = Aov::color;
    int light_samples = 0;   ///< samples per area light; 0 = each light's own `samples`
    int glossy_samples = 0;  ///< glossy rays per hit; 0 = each material's own
    int tile_size = 16;
    bool generic_kernel = false;  ///< packet path: the all-features kernel whatever the scene uses
    bool progress = false;        ///< progress on stderr (on a terminal)
    const char* progress_label = "render";  ///< what the progress line calls the render
    /// The part of the frame to render; empty (the default) is the whole frame. The film is the
    /// region's size. Every tile of the frame's grid that meets the region is rendered whole, so
    /// a pixel has the same value whatever region it is rendered in.
    PixelRect region;
};

struct RenderStats {
    uint64_t primary_rays = 0;
    uint64_t shadow_rays = 0;
    uint64_t reflection_rays = 0;
    uint64_t refraction_rays = 0;
    uint64_t glossy_rays = 0;
    uint64_t nan_samples = 0;  ///< samples with a NaN channel: counted, not averaged in
    uint64_t inf_samples = 0;  ///< samples with an infinite channel (and no NaN): likewise
    double seconds = 0.0;
    uint64_t bad_samples() const { return nan_samples + inf_samples; }
    /// Adds a tile's counts: the rays its shading spawned and its dropped samples.
    void add_tile(const ShadeCounts& shading, uint64_t nans, uint64_t infs) {
        shadow_rays += shading.shadow_rays, reflection_rays += shading.reflection_rays;
        refraction_rays += shading.refraction_rays, glossy_rays += shading.glossy_rays;
        nan_samples += nans, inf_samples += infs;
    }
    /// Adds o's ray and sample counts (not its time).
    void add_counts(const RenderStats& o) {
        primary_rays += o.primary_rays, shadow_rays += o.shadow_rays;
        reflection_rays += o.reflection_rays, refraction_rays += o.refraction_rays;
        glossy_rays += o.glossy_rays, nan_samples += o.nan_samples, inf_samples += o.inf_samples;
    }
    uint64_t total_rays() const {
        return primary_rays + shadow_rays + reflection_rays + refraction_rays + glossy_rays;
    }
};

struct RenderResult {
    /// Linear colour, or the raw AOV: the shading normal in [-1, 1] (0 where the ray misses),
    /// depth as the distance along the camera ray in scene units (0 where it misses), the BVH
    /// nodes visited (a count); averaged over the pixel's samples.
    Film film;
    RenderStats stats;
};

/// An AOV mapped for a PNG, and the scale it used, in words for the user.
struct AovView {
    Film film;
    std::string scale;  ///< e.g. "depth: white at 1.2, black at 45 and beyond (scene units)"
};

/// Maps a raw AOV film (RenderResult::film) to something to look at: normal * 0.5 + 0.5; depth
/// on a log scale from white at the nearest hit to black at the 98th percentile of the hit
/// distances (so that a floor running to the horizon does not take the range), misses black;
/// nodes visited
/// in false colour from 0 (blue) to the image's maximum (red). Colour passes through, with no
/// scale. Takes the film by value: pass an rvalue to map it in place.
AovView visualise_aov(Film film, Aov aov);

}  // namespace raylane
