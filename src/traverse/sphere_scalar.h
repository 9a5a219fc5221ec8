// traverse: ray/sphere intersection, the reference path (one ray, object space).
// Mirrored by sphere_packet.h.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/ray.h"
#include "scene/scene.h"
#include "traverse/local_geometry.h"

namespace raylane {

/// Nearest t in the open interval (ray.t_min, ray.t_max) where the ray meets the sphere, or
/// infinity. The far root is returned when the origin is inside. dir need not be unit length.
/// Haines, Guenther, Akenine-Moeller, "Precision Improvements for Ray/Sphere Intersection",
/// Ray Tracing Gems ch. 7 (2019): the discriminant from the perpendicular offset of the centre,
/// and the roots from the cancellation-free formula (accurate for far and for tiny spheres).
inline float intersect_sphere(const Sphere& s, const Ray& ray) {
    // quadratic a t^2 + 2 b t + c = 0 with f = org - center
    const vec3 f = ray.org - s.center;
    const vec3 d = ray.dir;
    const float r2 = s.radius * s.radius;
    const float a = glm::dot(d, d);
    const float b = glm::dot(f, d);
    const float c = glm::dot(f, f) - r2;

    // discriminant: b^2 - a c = a (r^2 - |l|^2), l = f - (b / a) d the perpendicular offset
    // (a = 0 or a NaN input gives NaN here and fails the positive test)
    const vec3 l = f - (b / a) * d;
    const float disc = a * (r2 - glm::dot(l, l));
    if (!(disc >= 0.0f)) return infinity;

    // roots: q = -(b + sign(b) sqrt(disc)), t0 = c / q, t1 = q / a
    const float q = -(b + std::copysign(std::sqrt(disc), b));
    const float t0 = c / q;
    const float t1 = q / a;
    const float t_lo = t0 < t1 ? t0 : t1;  // a NaN root ends up in t_hi
    const float t_hi = t0 < t1 ? t1 : t0;

    // accept: positive tests, so NaN never hits; the far root when the near one is behind
    if (t_lo > ray.t_min && t_lo < ray.t_max) return t_lo;
    if (t_hi > ray.t_min && t_hi < ray.t_max) return t_hi;
    return infinity;
}

/// Normal and uv at an object-space point p on the sphere. The normal is normalize(p - center)
/// (p need not lie exactly on the surface); uv = (phi / 2 pi, theta / pi) with phi the azimuth
/// around +y from +x towards +z and theta the angle from +y (v = 0 at the +y pole).
inline LocalGeometry geometry_sphere(const Sphere& s, vec3 p) {
    LocalGeometry g;
    g.normal = glm::normalize(p - s.center);
    const float theta = std::acos(std::clamp(g.normal.y, -1.0f, 1.0f));
    g.uv = vec2(azimuth_fraction(g.normal.x, g.normal.z), theta * std::numbers::inv_pi_v<float>);
    return g;
}

}  // namespace raylane
