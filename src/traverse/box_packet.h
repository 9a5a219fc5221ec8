// traverse: ray/box (axis-aligned box primitive) intersection, W rays against one box (the packet
// path, object space). Mirrors box_scalar.h step by step: a lane's t is bit-identical to the
// scalar result.
#pragma once

#include "core/ray_packet.h"
#include "scene/scene.h"
#include "traverse/box_scalar.h"
#include "traverse/slab_scalar.h"

namespace raylane::RAYLANE_ISA_NS {

/// Per lane, the nearest t in the open interval (t_min, t_max) where the ray meets the box, or
/// infinity (misses and inactive lanes); the exit t when the origin is inside. The slab test of
/// the scalar box with the same conventions and the same float operations; a lane the scalar
/// test leaves early (both planes of a slab NaN) is dropped from `live` instead.
template <int W>
inline vfloat<W> intersect_box(const Box& b, const RayPacket<W>& rays, vmask<W> active) {
    const vfloat<W> inf(infinity);
    if (none(active)) return inf;

    const vfloat<W> one(1.0f);
    const vfloat<W> org[3] = {rays.org.x, rays.org.y, rays.org.z};
    const vfloat<W> inv_dir[3] = {one / rays.dir.x, one / rays.dir.y, one / rays.dir.z};
    vfloat<W> t_enter(-infinity);
    vfloat<W> t_exit(infinity);
    vmask<W> live = active;
    for (int i = 0; i < 3; ++i) {
        // slab i: near/far by the sign of inv_dir (-0.0 gives -inf)
        const vfloat<W> t_lo = (vfloat<W>(b.lo[i]) - org[i]) * inv_dir[i];
        const vfloat<W> t_hi = (vfloat<W>(b.hi[i]) - org[i]) * inv_dir[i];
        const vmask<W> neg = inv_dir[i] < vfloat<W>(0.0f);
        const vfloat<W> t_near = select(neg, t_hi, t_lo);
        const vfloat<W> t_far = select(neg, t_lo, t_hi);

        // NaN: for one plane only (0 * inf, the ray lies in that face plane) the slab stays open
        // on that side; for both planes (a NaN input, or the ray lies in a slab of zero
        // thickness) the box is missed
        live = mask_and(live, mask_or(t_lo == t_lo, t_hi == t_hi));

        // interval: NaN-safe updates (a NaN leaves the bound unchanged)
        t_enter = select(t_near > t_enter, t_near, t_enter);
        t_exit = select(t_far < t_exit, t_far, t_exit);
    }
    // decide: closed test against the inflated exit (Ize 2013)
    live = mask_and(live, t_enter <= t_exit * vfloat<W>(slab_far_scale));
    if (none(live)) return inf;

    // accept: the entry, or the exit when the entry is not after t_min (origin inside)
    const vmask<W> take_enter = mask_and(t_enter > rays.t_min, t_enter < rays.t_max);
    const vmask<W> take_exit = mask_and(t_exit > rays.t_min, t_exit < rays.t_max);
    const vfloat<W> t = select(take_enter, t_enter, select(take_exit, t_exit, inf));
    return select(live, t, inf);
}

}  // namespace raylane::RAYLANE_ISA_NS
