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
/// positive acceptance test rejects both. T is the real type the arithmetic runs in.
template <typename T>
inline T intersect_plane(const Plane& p, const RayOf<T>& ray) {
    // distance: t = n.(point - org) / n.dir
    const Vec3Of<T> n(p.normal);
    const T t = glm::dot(n, Vec3Of<T>(p.point) - ray.org) / glm::dot(n, ray.dir);
    // accept
    return (t > ray.t_min && t < ray.t_max) ? t : infinity_of<T>;
}

/// The renderer's test: intersect_plane in float.
inline float intersect_plane(const Plane& p, const Ray& ray) {
    return intersect_plane<float>(p, ray_of<float>(ray));
}

/// Normal and uv at an object-space point on the plane. The normal is the plane's (both sides
/// share it); uv are the coordinates of p_hit - point in the tangent frame (t1, t2) of
/// Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin, "Building an Orthonormal Basis,
/// Revisited", JCGT 2017 (a fixed frame for each normal, accurate for every normal).
/// The plane's unit normal and tangent frame (t1, t2, n): Duff et al., "Building an
/// Orthonormal Basis, Revisited", JCGT 2017. Shared by both paths' uv.
template <typename T>
struct PlaneFrameOf {
    Vec3Of<T> n, t1, t2;
};
using PlaneFrame = PlaneFrameOf<float>;

template <typename T = float>
inline PlaneFrameOf<T> plane_frame(const Plane& p) {
    const Vec3Of<T> n = glm::normalize(Vec3Of<T>(p.normal));
    const T sign = std::copysign(T(1), n.z);
    const T a = T(-1) / (sign + n.z);
    const T b = n.x * n.y * a;
    return {n, Vec3Of<T>(T(1) + sign * n.x * n.x * a, sign * b, -sign * n.x),
            Vec3Of<T>(b, sign + n.y * n.y * a, -n.y)};
}

template <typename T>
inline LocalGeometryOf<T> geometry_plane(const Plane& p, Vec3Of<T> p_hit) {
    // frame
    const PlaneFrameOf<T> f = plane_frame<T>(p);

    // coordinates
    const Vec3Of<T> q = p_hit - Vec3Of<T>(p.point);
    LocalGeometryOf<T> g;
    g.normal = f.n;
    g.uv = glm::vec<2, T>(glm::dot(q, f.t1), glm::dot(q, f.t2));
    return g;
}

}  // namespace raylane
