// traverse: ray/plane intersection (infinite plane, kept outside the BVH), the reference path
// (one ray, object space). Mirrored by plane_packet.h.
#pragma once

#include <cmath>

#include "core/ray.h"
#include "scene/scene.h"
#include "traverse/local_geometry.h"

namespace raylane {

/// t in the open interval (ray.t_min, ray.t_max) where the ray meets the plane, or infinity.
/// A ray parallel to the plane divides by zero (+-inf, or NaN when it lies in the plane); the
/// positive acceptance test rejects both.
inline float intersect_plane(const Plane& p, const Ray& ray) {
    // distance: t = n.(point - org) / n.dir
    const float t = glm::dot(p.normal, p.point - ray.org) / glm::dot(p.normal, ray.dir);
    // accept
    return (t > ray.t_min && t < ray.t_max) ? t : infinity;
}

/// Normal and uv at an object-space point on the plane. The normal is the plane's (both sides
/// share it); uv are the coordinates of p_hit - point in the tangent frame (t1, t2) of
/// Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin, "Building an Orthonormal Basis,
/// Revisited", JCGT 2017 (a fixed frame for each normal, accurate for every normal).
/// The plane's unit normal and tangent frame (t1, t2, n): Duff et al., "Building an
/// Orthonormal Basis, Revisited", JCGT 2017. Shared by both paths' uv.
struct PlaneFrame {
    vec3 n, t1, t2;
};
inline PlaneFrame plane_frame(const Plane& p) {
    const vec3 n = glm::normalize(p.normal);
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {n, vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x),
            vec3(b, sign + n.y * n.y * a, -n.y)};
}

inline LocalGeometry geometry_plane(const Plane& p, vec3 p_hit) {
    // frame
    const PlaneFrame f = plane_frame(p);

    // coordinates
    const vec3 q = p_hit - p.point;
    LocalGeometry g;
    g.normal = f.n;
    g.uv = vec2(glm::dot(q, f.t1), glm::dot(q, f.t2));
    return g;
}

}  // namespace raylane
