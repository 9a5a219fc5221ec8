// traverse: ray/box slab test for BVH nodes (Aabb, BvhNode bounds), the reference path.
// Mirrored by slab_packet.h.
#pragma once

#include "core/ray.h"
#include "traverse/local_geometry.h"

namespace raylane {

/// pbrt's gamma_n = n eps / (1 - n eps) with eps = 2^-24 for float (2^-53 for double): the
/// relative error bound of n correctly rounded operations in T (Pharr, Jakob, Humphreys,
/// "Physically Based Rendering").
template <typename T = float>
constexpr T rounding_gamma(int n) {
    const T eps = std::numeric_limits<T>::epsilon() / T(2);
    return static_cast<T>(n) * eps / (T(1) - static_cast<T>(n) * eps);
}

/// The far slab distance is scaled by this so that rounding can never make a box that the
/// ray touches look missed (Ize, "Robust BVH Ray Traversal", JCGT 2013). Shared by the box
/// primitive and both slab paths; slab_far_scale_of<double> is the double oracle's.
template <typename T>
inline constexpr T slab_far_scale_of = T(1) + T(2) * rounding_gamma<T>(3);
inline constexpr float slab_far_scale = slab_far_scale_of<float>;

/// A ray prepared for slab tests.
template <typename T>
struct SlabRayOf {
    Vec3Of<T> org{T(0)};
    /// exact reciprocal of dir (division, never rcp)
    Vec3Of<T> inv_dir{infinity_of<T>, infinity_of<T>, T(1)};
};
using SlabRay = SlabRayOf<float>;

template <typename T>
inline SlabRayOf<T> make_slab_ray(const RayOf<T>& ray) {
    return {ray.org, Vec3Of<T>(T(1) / ray.dir.x, T(1) / ray.dir.y, T(1) / ray.dir.z)};
}
inline SlabRay make_slab_ray(const Ray& ray) { return make_slab_ray<float>(ray_of<float>(ray)); }

/// True when the ray touches the box [lo, hi] within the closed interval [t_min, t_max];
/// t_near is then the entry distance clamped to t_min (never NaN when t_min is not).
/// Conservative: a box that a primitive inside it is hit in is never missed, a box of zero
/// thickness included. A ray lying in a face plane (0 * inf = NaN) counts as touching that slab.
template <typename T>
inline bool intersect_slab(const SlabRayOf<T>& r, Vec3Of<T> lo, Vec3Of<T> hi, T t_min, T t_max,
                           T& t_near) {
    T t0 = t_min;
    T t1 = t_max;
    for (int i = 0; i < 3; ++i) {
        // slab i: distances to its two planes, near/far by the sign of inv_dir (so that -0.0,
        // whose reciprocal is -inf, is ordered like any negative component)
        const T t_lo = (lo[i] - r.org[i]) * r.inv_dir[i];
        const T t_hi = (hi[i] - r.org[i]) * r.inv_dir[i];
        const bool neg = r.inv_dir[i] < T(0);
        const T t_enter = neg ? t_hi : t_lo;
        const T t_exit = (neg ? t_lo : t_hi) * slab_far_scale_of<T>;

        // interval: a NaN distance compares false and leaves the running bound unchanged
        t0 = t_enter > t0 ? t_enter : t0;
        t1 = t_exit < t1 ? t_exit : t1;
    }
    // closed test
    t_near = t0;
    return t0 <= t1;
}

}  // namespace raylane
