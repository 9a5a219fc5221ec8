// traverse: closest-hit and any-hit queries of one ray against the whole scene (both BVH levels),
// the reference path. Mirrored by intersect_packet.h.
#pragma once

#include "accel/bvh.h"
#include "core/ray.h"
#include "scene/scene.h"

namespace raylane {

/// How far above the current hit's t (in float steps) nodes and primitives are still tested, so
/// that ties reach the tie-break below (intersect_scalar.cpp: t_limit; same in the packet path).
inline constexpr int32_t tie_ulps = 4;

/// The closest hit in (ray.t_min, ray.t_max). Ties in t go to the smaller object index, then the
/// smaller primitive index, so the answer does not depend on traversal order.
Hit intersect_closest(const Scene& scene, const Accel& accel, const Ray& ray,
                      TraversalStats* stats = nullptr);

/// True when anything is hit in (ray.t_min, ray.t_max) (shadow rays).
bool intersect_any(const Scene& scene, const Accel& accel, const Ray& ray,
                   TraversalStats* stats = nullptr);

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
SurfacePoint surface_at(const Scene& scene, const Ray& ray, const Hit& hit);

}  // namespace raylane
