// traverse: the surface at a hit of the reference path (surface_at): position, normals, uv,
// material. Mirrored by surface_packet.h.
#pragma once

#include "core/ray.h"
#include "scene/scene.h"

namespace raylane {

/// Everything shading needs about a hit, in world space.
struct SurfacePoint {
    vec3 position{0.0f};
    vec3 geometric_normal{0.0f, 1.0f, 0.0f};  ///< unit, on the side the shape's winding gives
    vec3 shading_normal{0.0f, 1.0f, 0.0f};    ///< unit; interpolated vertex normal for meshes
    vec2 uv{0.0f};
    uint32_t material = 0;
};

/// Evaluates position, normals and uv at a hit found by intersect_closest. uv is 0 on spheres
/// and cylinders whose material reads neither a texture nor a normal map (it would go unused).
SurfacePoint surface_at(const SceneData& scene, const Ray& ray, const Hit& hit);

}  // namespace raylane
