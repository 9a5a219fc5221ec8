// traverse: ray/sphere intersection, W rays against one sphere (the packet path, object space).
// Mirrors sphere_scalar.h step by step: a lane's t is bit-identical to the scalar result.
#pragma once

#include "core/ray_packet.h"
#include "scene/scene.h"
#include "traverse/sphere_scalar.h"

namespace raylane {

/// Per lane, the nearest t in the open interval (t_min, t_max) where the ray meets the sphere,
/// or infinity (misses and inactive lanes). The far root when the origin is inside. The same
/// float operations in the same order as the scalar test; its branches become masks.
/// Haines, Guenther, Akenine-Moeller, "Precision Improvements for Ray/Sphere Intersection",
/// Ray Tracing Gems ch. 7 (2019).
template <int W>
inline vfloat<W> intersect_sphere(const Sphere& s, const RayPacket<W>& rays, vmask<W> active) {
    const vfloat<W> inf(infinity);
    if (none(active)) return inf;

    // quadratic a t^2 + 2 b t + c = 0 with f = org - center
    const Vec3<W> f = rays.org - make_vec3<W>(s.center.x, s.center.y, s.center.z);
    const Vec3<W>& d = rays.dir;
    const vfloat<W> r2(s.radius * s.radius);
    const vfloat<W> a = dot<W>(d, d);
    const vfloat<W> b = dot<W>(f, d);
    const vfloat<W> c = dot<W>(f, f) - r2;

    // discriminant: b^2 - a c = a (r^2 - |l|^2), l = f - (b / a) d the perpendicular offset
    // (a = 0 or a NaN input gives NaN here and fails the positive test)
    const Vec3<W> l = f - (b / a) * d;
    const vfloat<W> disc = a * (r2 - dot<W>(l, l));
    const vmask<W> live = mask_and(disc >= vfloat<W>(0.0f), active);
    if (none(live)) return inf;

    // roots: q = -(b + sign(b) sqrt(disc)), t0 = c / q, t1 = q / a (the sqrt of dead lanes is
    // taken of 0, so no lane raises invalid)
    const vfloat<W> root = sqrt(select(live, disc, vfloat<W>(0.0f)));
    const vfloat<W> q = neg(b + copysign(root, b));
    const vfloat<W> t0 = c / q;
    const vfloat<W> t1 = q / a;
    const vmask<W> ordered = t0 < t1;
    const vfloat<W> t_lo = select(ordered, t0, t1);  // a NaN root ends up in t_hi
    const vfloat<W> t_hi = select(ordered, t1, t0);

    // accept: positive tests, so NaN never hits; the far root when the near one is behind
    const vmask<W> take_lo = mask_and(t_lo > rays.t_min, t_lo < rays.t_max);
    const vmask<W> take_hi = mask_and(t_hi > rays.t_min, t_hi < rays.t_max);
    const vfloat<W> t = select(take_lo, t_lo, select(take_hi, t_hi, inf));
    return select(live, t, inf);
}

}  // namespace raylane
