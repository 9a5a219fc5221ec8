// traverse: ray/sphere intersection, W rays against one sphere (the packet path, object space).
// Mirrors sphere_scalar.h step by step: a lane's t is bit-identical to the scalar result.
#pragma once

#include "core/ray_packet.h"
#include "scene/scene.h"
#include "traverse/sphere_scalar.h"

namespace raylane::RAYLANE_ISA_NS {

// ---- error-free transformations ---------------------------------------------------------------

/// Per lane, a + b = sum + err exactly (Knuth's TwoSum). Returns sum.
template <int W>
inline vfloat<W> two_sum(const vfloat<W>& a, const vfloat<W>& b, vfloat<W>& err) {
    const vfloat<W> sum = a + b;
    const vfloat<W> b_part = sum - a;
    err = (a - (sum - b_part)) + (b - b_part);
    return sum;
}

/// Per lane, a * b = product + err exactly (the error from one FMA). Returns product.
template <int W>
inline vfloat<W> two_product(const vfloat<W>& a, const vfloat<W>& b, vfloat<W>& err) {
    const vfloat<W> product = a * b;
    err = fma(a, b, neg(product));
    return product;
}

/// Per lane, x . y as hi + lo (Ogita, Rump, Oishi's Dot2). Returns hi.
template <int W>
inline vfloat<W> dot_compensated(const Vec3<W>& x, const Vec3<W>& y, vfloat<W>& lo) {
    vfloat<W> e_x, e_y, e_z, e_xy, e_xyz;
    const vfloat<W> p_x = two_product<W>(x.x, y.x, e_x);
    const vfloat<W> p_y = two_product<W>(x.y, y.y, e_y);
    const vfloat<W> p_z = two_product<W>(x.z, y.z, e_z);
    const vfloat<W> sum_xy = two_sum<W>(p_x, p_y, e_xy);
    const vfloat<W> sum = two_sum<W>(sum_xy, p_z, e_xyz);
    lo = ((e_x + e_y) + e_z) + (e_xy + e_xyz);
    return sum;
}

// ---- quadratic ---------------------------------------------------------------------------------

/// Per lane, f_lo with org - center = f + f_lo exactly, f = org - center rounded.
template <int W>
inline Vec3<W> center_offset_error(const Sphere& s, const RayPacket<W>& rays) {
    Vec3<W> f_lo;
    two_sum<W>(rays.org.x, vfloat<W>(-s.center.x), f_lo.x);
    two_sum<W>(rays.org.y, vfloat<W>(-s.center.y), f_lo.y);
    two_sum<W>(rays.org.z, vfloat<W>(-s.center.z), f_lo.z);
    return f_lo;
}

/// Per lane, b = (f + f_lo) . d, rounded once (nearly).
template <int W>
inline vfloat<W> half_linear_term(const Vec3<W>& f, const Vec3<W>& f_lo, const Vec3<W>& d) {
    vfloat<W> lo;
    const vfloat<W> hi = dot_compensated<W>(f, d, lo);
    return hi + (lo + dot<W>(f_lo, d));
}

/// Per lane, c = |f + f_lo|^2 - r^2, rounded once (nearly).
template <int W>
inline vfloat<W> constant_term(const Vec3<W>& f, const Vec3<W>& f_lo, const vfloat<W>& r) {
    vfloat<W> ff_lo, rr_lo, e_c;
    const vfloat<W> ff = dot_compensated<W>(f, f, ff_lo);
    const vfloat<W> rr = two_product<W>(r, r, rr_lo);
    const vfloat<W> hi = two_sum<W>(ff, neg(rr), e_c);
    return hi + ((e_c + (ff_lo - rr_lo)) + vfloat<W>(2.0f) * dot<W>(f, f_lo));
}

/// Per lane, the discriminant as a (r^2 - |l|^2), l = f - (b / a) d (Haines et al.).
template <int W>
inline vfloat<W> perpendicular_discriminant(const Vec3<W>& f, const Vec3<W>& d, const vfloat<W>& a,
                                            const vfloat<W>& b, const vfloat<W>& r2) {
    const Vec3<W> l = f - (b / a) * d;
    return a * (r2 - dot<W>(l, l));
}

// ---- intersection ------------------------------------------------------------------------------

/// Per lane, the nearest t in the open interval (t_min, t_max) where the ray meets the sphere,
/// or infinity (misses and inactive lanes). The far root when the origin is inside. The same
/// float operations in the same order as the scalar test; its branches become masks.
/// Haines, Guenther, Akenine-Moeller, "Precision Improvements for Ray/Sphere Intersection",
/// Ray Tracing Gems ch. 7 (2019); near the sphere b and c carried past float's rounding.
template <int W>
inline vfloat<W> intersect_sphere(const Sphere& s, const RayPacket<W>& rays, vmask<W> active) {
    const vfloat<W> inf(infinity);
    if (none(active)) return inf;

    // quadratic a t^2 + 2 b t + c = 0 with f = org - center
    const Vec3<W> f = rays.org - make_vec3<W>(s.center.x, s.center.y, s.center.z);
    const Vec3<W>& d = rays.dir;
    const vfloat<W> r(s.radius);
    const vfloat<W> r2(s.radius * s.radius);
    const vfloat<W> a = dot<W>(d, d);
    vfloat<W> b = dot<W>(f, d);
    vfloat<W> c = dot<W>(f, f) - r2;

    // discriminant b^2 - a c: in lanes near the sphere (c < r^2) from b and c recomputed past
    // float's rounding, as written; in the others Haines et al.'s form. Each form is computed
    // only when some active lane takes it.
    const vmask<W> near = mask_and(c < r2, active);
    vfloat<W> disc = inf;
    if (any(mask_andnot(active, near))) disc = perpendicular_discriminant<W>(f, d, a, b, r2);
    if (any(near)) {
        const Vec3<W> f_lo = center_offset_error<W>(s, rays);
        b = select(near, half_linear_term<W>(f, f_lo, d), b);
        c = select(near, constant_term<W>(f, f_lo, r), c);
        disc = select(near, b * b - a * c, disc);
    }
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

}  // namespace raylane::RAYLANE_ISA_NS
