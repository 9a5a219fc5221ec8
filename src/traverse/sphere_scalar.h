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
/// T is the real type the arithmetic runs in (the sphere's float fields are converted to it).
/// Haines, Guenther, Akenine-Moeller, "Precision Improvements for Ray/Sphere Intersection",
/// Ray Tracing Gems ch. 7 (2019): the discriminant from the perpendicular offset of the centre,
/// and the roots from the cancellation-free formula (accurate for far and for tiny spheres).
template <typename T>
inline T intersect_sphere(const Sphere& s, const RayOf<T>& ray) {
    // quadratic a t^2 + 2 b t + c = 0 with f = org - center
    const Vec3Of<T> f = ray.org - Vec3Of<T>(s.center);
    const Vec3Of<T> d = ray.dir;
    const T r2 = static_cast<T>(s.radius) * static_cast<T>(s.radius);
    const T a = glm::dot(d, d);
    const T b = glm::dot(f, d);
    const T c = glm::dot(f, f) - r2;

    // discriminant: b^2 - a c = a (r^2 - |l|^2), l = f - (b / a) d the perpendicular offset
    // (a = 0 or a NaN input gives NaN here and fails the positive test)
    const Vec3Of<T> l = f - (b / a) * d;
    const T disc = a * (r2 - glm::dot(l, l));
    if (!(disc >= T(0))) return infinity_of<T>;

    // roots: q = -(b + sign(b) sqrt(disc)), t0 = c / q, t1 = q / a
    const T q = -(b + std::copysign(std::sqrt(disc), b));
    const T t0 = c / q;
    const T t1 = q / a;
    const T t_lo = t0 < t1 ? t0 : t1;  // a NaN root ends up in t_hi
    const T t_hi = t0 < t1 ? t1 : t0;

    // accept: positive tests, so NaN never hits; the far root when the near one is behind
    if (t_lo > ray.t_min && t_lo < ray.t_max) return t_lo;
    if (t_hi > ray.t_min && t_hi < ray.t_max) return t_hi;
    return infinity_of<T>;
}

/// The renderer's test: intersect_sphere in float.
inline float intersect_sphere(const Sphere& s, const Ray& ray) {
    return intersect_sphere<float>(s, ray_of<float>(ray));
}

/// Normal and uv at an object-space point p on the sphere. The normal is normalize(p - center)
/// (p need not lie exactly on the surface); uv = (phi / 2 pi, theta / pi) with phi the azimuth
/// around +y from +x towards +z and theta the angle from +y (v = 0 at the +y pole). With
/// with_uv false, uv stays 0 (no acos and atan2: surface_at asks for uv only when the material
/// reads a texture or a normal map).
template <typename T>
inline LocalGeometryOf<T> geometry_sphere(const Sphere& s, Vec3Of<T> p, bool with_uv = true) {
    LocalGeometryOf<T> g;
    g.normal = glm::normalize(p - Vec3Of<T>(s.center));
    if (!with_uv) return g;
    const T theta = std::acos(std::clamp(g.normal.y, T(-1), T(1)));
    g.uv =
        glm::vec<2, T>(azimuth_fraction(g.normal.x, g.normal.z), theta * std::numbers::inv_pi_v<T>);
    return g;
}

}  // namespace raylane
