// traverse: ray/box slab test for BVH nodes, W rays against one box (the packet path).
// Mirrors slab_scalar.h step by step.
#pragma once

#include "core/ray_packet.h"
#include "traverse/slab_scalar.h"

namespace raylane::RAYLANE_ISA_NS {

/// W rays prepared for slab tests.
template <int W>
struct SlabPacket {
    Vec3<W> org;
    Vec3<W> inv_dir;  ///< exact reciprocal of dir (division, never rcp)
};

template <int W>
inline SlabPacket<W> make_slab_ray(const RayPacket<W>& rays) {
    const vfloat<W> one(1.0f);
    return {rays.org, {one / rays.dir.x, one / rays.dir.y, one / rays.dir.z}};
}

/// The lanes of `active` whose ray touches the box [lo, hi] within [t_min, t_max]; t_near is
/// the entry distance clamped to t_min. Same arithmetic as the scalar test, lane by lane.
template <int W>
inline vmask<W> intersect_slab(const SlabPacket<W>& r, vec3 lo, vec3 hi, const vfloat<W>& t_min,
                               const vfloat<W>& t_max, vfloat<W>& t_near, vmask<W> active) {
    vfloat<W> t0 = t_min;
    vfloat<W> t1 = t_max;
    const vfloat<W>* org[3] = {&r.org.x, &r.org.y, &r.org.z};
    const vfloat<W>* inv[3] = {&r.inv_dir.x, &r.inv_dir.y, &r.inv_dir.z};
    for (int i = 0; i < 3; ++i) {
        // slab i
        const vfloat<W> t_lo = (vfloat<W>(lo[i]) - *org[i]) * *inv[i];
        const vfloat<W> t_hi = (vfloat<W>(hi[i]) - *org[i]) * *inv[i];
        const vmask<W> neg = *inv[i] < vfloat<W>(0.0f);
        const vfloat<W> t_enter = select(neg, t_hi, t_lo);
        const vfloat<W> t_exit = select(neg, t_lo, t_hi) * vfloat<W>(slab_far_scale);
        // interval: max(a, b) is a > b ? a : b and min(a, b) a < b ? a : b (simd/math.h), the
        // scalar test's expressions, NaN distances included, in one instruction each
        t0 = max(t_enter, t0);
        t1 = min(t_exit, t1);
    }
    // closed test
    t_near = t0;
    return mask_and(t0 <= t1, active);
}

}  // namespace raylane::RAYLANE_ISA_NS
