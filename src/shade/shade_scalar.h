// shade: the radiance along one ray of a path, the reference path: local shading (diffuse and
// specular lobes, point, directional and area lights with shadow rays, glossy rays), mirror
// reflection, Fresnel refraction with Beer's law, textures, normal and environment maps.
// Recursive and plain. Mirrored by shade_packet.h (the same terms, for packets of hits grouped by
// material).
#pragma once

#include <cstdint>

#include "accel/bvh.h"
#include "core/ray.h"
#include "scene/scene.h"

namespace raylane {

/// Rays traced while shading, by kind.
struct ShadeCounts {
    uint64_t shadow_rays = 0;
    uint64_t reflection_rays = 0;  ///< mirror rays and glass reflections
    uint64_t refraction_rays = 0;
    uint64_t glossy_rays = 0;
    void add(const ShadeCounts& o) {
        shadow_rays += o.shadow_rays;
        reflection_rays += o.reflection_rays;
        refraction_rays += o.refraction_rays;
        glossy_rays += o.glossy_rays;
    }
};

/// The counters every random number of one camera sample derives from (core/rng.h).
struct SampleIndex {
    uint32_t pixel = 0, sample = 0, seed = 0;
};

/// Sample-count overrides of the error-vs-time sweep (RenderParams); 0 = the scene's own.
struct ShadeParams {
    int light_samples = 0;
    int glossy_samples = 0;
};

/// One ray of the path tree: the camera ray, or a reflected, refracted or glossy ray.
struct PathRay {
    Ray ray;
    uint32_t key = 0;  ///< path key (core/rng.h child_key): the random dimensions at its hit
    int reflection_depth = 0;
    int refraction_depth = 0;
    bool local_only = false;  ///< glossy rays: the hit is shaded locally and spawns no rays
    int32_t env_map = -1;     ///< texture seen on a miss (a per-object reflection map); -1 = scene
};

/// Radiance arriving along the ray, and the distance to what it hit (infinity on a miss; Beer's
/// law needs it).
struct PathResult {
    vec3 radiance{0.0f};
    float t = infinity;
};

PathResult trace_path(const SceneData& scene, const Accel& accel, const PathRay& path,
                      const SampleIndex& index, const ShadeParams& params, ShadeCounts& counts);

/// Radiance of a ray that leaves the scene: the map `env_map` (or the scene's environment) in
/// the ray's direction, else the background colour.
vec3 miss_radiance(const SceneData& scene, int32_t env_map, vec3 dir);

/// The number of samples area light `light` takes per shading point.
inline int light_sample_count(const Light& light, const ShadeParams& params) {
    if (!light.is_area()) return 1;
    return params.light_samples > 0 ? params.light_samples : light.samples;
}

/// The number of glossy rays material `m` traces per hit.
inline int glossy_sample_count(const Material& m, const ShadeParams& params) {
    return params.glossy_samples > 0 ? params.glossy_samples : m.glossy_samples;
}

}  // namespace raylane
