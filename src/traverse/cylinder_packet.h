// traverse: ray/cylinder intersection (finite, capped, around +y), W rays against one cylinder
// (the packet path, object space). Mirrors cylinder_scalar.h step by step: a lane's t is
// bit-identical to the scalar result.
#pragma once

#include "core/ray_packet.h"
#include "scene/scene.h"
#include "traverse/cylinder_scalar.h"

namespace raylane::RAYLANE_ISA_NS {

/// Per lane, the nearest t in the open interval (t_min, t_max) where the ray meets the cylinder
/// x^2 + z^2 <= r^2, 0 <= y <= h (side and both caps), or infinity (misses and inactive lanes);
/// the exit t when the origin is inside. The same float operations as the scalar test; its
/// branches become masks: `side` (a > 0) selects the side interval and gates the side
/// candidates before they are combined with the caps, so the ±inf / NaN roots of lanes with
/// a = 0 never reach the result (numerics.md §5). Closed predicates as t-intervals, as in the
/// scalar test; side roots after Haines, Guenther, Akenine-Moeller, Ray Tracing Gems ch. 7, 2019.
template <int W>
inline vfloat<W> intersect_cylinder(const Cylinder& cyl, const RayPacket<W>& rays,
                                    vmask<W> active) {
    const vfloat<W> inf(infinity);
    if (none(active)) return inf;

    const Vec3<W>& o = rays.org;
    const Vec3<W>& d = rays.dir;
    const vfloat<W> r2(cyl.radius * cyl.radius);
    const vfloat<W> zero(0.0f);

    // side: the infinite cylinder as the interval [s_lo, s_hi] of t (a t^2 + 2 b t + c = 0)
    const vfloat<W> a = d.x * d.x + d.z * d.z;
    const vfloat<W> b = o.x * d.x + o.z * d.z;
    const vfloat<W> c = o.x * o.x + o.z * o.z - r2;
    const vmask<W> side = a > zero;
    vmask<W> live = active;
    vfloat<W> s_lo(-infinity);
    vfloat<W> s_hi(infinity);
    if (any(mask_and(side, live))) {
        // discriminant from the perpendicular offset of the axis: b^2 - a c = a (r^2 - |l|^2)
        const vfloat<W> lx = o.x - (b / a) * d.x;
        const vfloat<W> lz = o.z - (b / a) * d.z;
        const vfloat<W> disc = a * (r2 - (lx * lx + lz * lz));
        const vmask<W> real = disc >= zero;
        live = mask_andnot(live, mask_andnot(side, real));
        const vfloat<W> root = sqrt(select(mask_and(side, real), disc, zero));
        const vfloat<W> q = neg(b + copysign(root, b));
        const vfloat<W> t0 = c / q;
        const vfloat<W> t1 = q / a;
        const vmask<W> ordered = t0 < t1;
        s_lo = select(side, select(ordered, t0, t1), s_lo);
        s_hi = select(side, select(ordered, t1, t0), s_hi);
    }
    // parallel to the axis (or NaN), outside the closed disc
    live = mask_andnot(live, mask_andnot(mask_not(side), c <= zero));
    if (none(live)) return inf;

    // caps: the slab 0 <= y <= h as the interval [y_lo, y_hi] of t, near/far by the sign bit of
    // dy. A NaN distance for one plane (0 / 0, the ray lies in that cap plane) leaves that end
    // open; for both (a NaN input, or height 0) the cylinder is missed
    const vfloat<W> t_bottom = (zero - o.y) / d.y;
    const vfloat<W> t_top = (vfloat<W>(cyl.height) - o.y) / d.y;
    live = mask_and(live, mask_or(t_bottom == t_bottom, t_top == t_top));
    if (none(live)) return inf;
    const vmask<W> down = sign_bit(d.y);
    const vfloat<W> y_near = select(down, t_top, t_bottom);
    const vfloat<W> y_far = select(down, t_bottom, t_top);
    const vfloat<W> y_lo = select(y_near > vfloat<W>(-infinity), y_near, vfloat<W>(-infinity));
    const vfloat<W> y_hi = select(y_far < inf, y_far, inf);

    // accept: smallest candidate in (t_min, t_max) lying in the other interval (closed); the side
    // candidates only where a > 0
    auto in = [&](const vfloat<W>& x, const vfloat<W>& lo, const vfloat<W>& hi,
                  const vfloat<W>& t_best) {
        return mask_and(
            mask_and(mask_and(x >= lo, x <= hi), mask_and(x > rays.t_min, x < rays.t_max)),
            x < t_best);
    };
    vfloat<W> t = inf;
    t = select(mask_and(side, in(s_lo, y_lo, y_hi, t)), s_lo, t);
    t = select(mask_and(side, in(s_hi, y_lo, y_hi, t)), s_hi, t);
    t = select(in(y_lo, s_lo, s_hi, t), y_lo, t);
    t = select(in(y_hi, s_lo, s_hi, t), y_hi, t);
    return select(live, t, inf);
}

}  // namespace raylane::RAYLANE_ISA_NS
