// traverse: ray/box slab test for BVH nodes (Aabb, BvhNode bounds), the reference path.
// Mirrored by slab_packet.h.
#pragma once

#include "core/ray.h"

namespace raylane {

/// pbrt's gamma_n = n eps / (1 - n eps) with eps = 2^-24: the relative error bound of n
/// correctly rounded float operations (Pharr, Jakob, Humphreys, "Physically Based Rendering").
constexpr float rounding_gamma(int n) {
    const float eps = 0x1.0p-24f;
    return static_cast<float>(n) * eps / (1.0f - static_cast<float>(n) * eps);
}

/// The far slab distance is scaled by this so that rounding can never make a box that the
/// ray touches look missed (Ize, "Robust BVH Ray Traversal", JCGT 2013). Shared by the box
/// primitive and both slab paths.
inline constexpr float slab_far_scale = 1.0f + 2.0f * rounding_gamma(3);

/// A ray prepared for slab tests.
struct SlabRay {
    vec3 org{0.0f};
    vec3 inv_dir{infinity, infinity, 1.0f};  ///< exact reciprocal of dir (division, never rcp)
};

inline SlabRay make_slab_ray(const Ray& ray) { return {ray.org, reciprocal(ray.dir)}; }

/// True when the ray touches the box [lo, hi] within the closed interval [t_min, t_max];
/// t_near is then the entry distance clamped to t_min (never NaN when t_min is not).
/// Conservative: a box that a primitive inside it is hit in is never missed, a box of zero
/// thickness included. A ray lying in a face plane (0 * inf = NaN) counts as touching that slab.
inline bool intersect_slab(const SlabRay& r, vec3 lo, vec3 hi, float t_min, float t_max,
                           float& t_near) {
    float t0 = t_min;
    float t1 = t_max;
    for (int i = 0; i < 3; ++i) {
        // slab i: distances to its two planes, near/far by the sign of inv_dir (so that -0.0,
        // whose reciprocal is -inf, is ordered like any negative component)
        const float t_lo = (lo[i] - r.org[i]) * r.inv_dir[i];
        const float t_hi = (hi[i] - r.org[i]) * r.inv_dir[i];
        const bool neg = r.inv_dir[i] < 0.0f;
        const float t_enter = neg ? t_hi : t_lo;
        const float t_exit = (neg ? t_lo : t_hi) * slab_far_scale;

        // interval: a NaN distance compares false and leaves the running bound unchanged
        t0 = t_enter > t0 ? t_enter : t0;
        t1 = t_exit < t1 ? t_exit : t1;
    }
    // closed test
    t_near = t0;
    return t0 <= t1;
}

}  // namespace raylane
