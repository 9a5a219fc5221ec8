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

/// The ray moved into an object's space; t is unchanged because the map is affine.
inline Ray to_object_space(const Object& object, const Ray& ray) {
    if (!object.has_transform) return ray;
    Ray r = ray;
    r.org = vec3(object.object_from_world * glm::vec4(ray.org, 1.0f));
    r.dir = vec3(object.object_from_world * glm::vec4(ray.dir, 0.0f));
    return r;
}

/// The closest hit in (ray.t_min, ray.t_max). Ties in t go to the smaller object index, then the
/// smaller primitive index, so the answer does not depend on traversal order.
Hit intersect_closest(const SceneData& scene, const Accel& accel, const Ray& ray,
                      TraversalStats* stats = nullptr);

/// True when anything is hit in (ray.t_min, ray.t_max) (shadow rays).
bool intersect_any(const SceneData& scene, const Accel& accel, const Ray& ray,
                   TraversalStats* stats = nullptr);

}  // namespace raylane
