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

// ---- error-free transformations ---------------------------------------------------------------

/// a + b = sum + err exactly, whatever the magnitudes (Knuth's TwoSum, The Art of Computer
/// Programming vol. 2, 4.2.2). Returns sum, the rounded a + b.
template <typename T>
inline T two_sum(T a, T b, T& err) {
    const T sum = a + b;
    const T b_part = sum - a;
    err = (a - (sum - b_part)) + (b - b_part);
    return sum;
}

/// a * b = product + err exactly (the error from one FMA; exact unless a * b underflows).
/// Returns product, the rounded a * b.
template <typename T>
inline T two_product(T a, T b, T& err) {
    const T product = a * b;
    err = std::fma(a, b, -product);
    return product;
}

/// x . y as an unevaluated sum hi + lo, nearly as if computed in twice the precision: exact
/// products and a running sum whose rounding errors are carried in lo (Ogita, Rump, Oishi,
/// "Accurate Sum and Dot Product", SIAM J. Sci. Comput. 2005, Dot2). Returns hi.
template <typename T>
inline T dot_compensated(Vec3Of<T> x, Vec3Of<T> y, T& lo) {
    T e_x, e_y, e_z, e_xy, e_xyz;
    const T p_x = two_product(x.x, y.x, e_x);
    const T p_y = two_product(x.y, y.y, e_y);
    const T p_z = two_product(x.z, y.z, e_z);
    const T sum_xy = two_sum(p_x, p_y, e_xy);
    const T sum = two_sum(sum_xy, p_z, e_xyz);
    lo = ((e_x + e_y) + e_z) + (e_xy + e_xyz);
    return sum;
}

// ---- quadratic ---------------------------------------------------------------------------------

/// f_lo with org - center = f + f_lo exactly, f = org - center rounded (TwoSum per component).
/// A ray starting 1 above a sphere of radius 1e4 at coordinates of 1e4 keeps in f_lo the digits
/// of its height that f loses.
template <typename T>
inline Vec3Of<T> center_offset_error(const Sphere& s, const RayOf<T>& ray) {
    const Vec3Of<T> center(s.center);
    Vec3Of<T> f_lo;
    two_sum(ray.org.x, -center.x, f_lo.x);
    two_sum(ray.org.y, -center.y, f_lo.y);
    two_sum(ray.org.z, -center.z, f_lo.z);
    return f_lo;
}

/// b = (f + f_lo) . d, rounded once (nearly): a grazing ray makes f . d cancel.
template <typename T>
inline T half_linear_term(Vec3Of<T> f, Vec3Of<T> f_lo, Vec3Of<T> d) {
    T lo;
    const T hi = dot_compensated(f, d, lo);
    return hi + (lo + glm::dot(f_lo, d));
}

/// c = |f + f_lo|^2 - r^2 (the power of the ray origin with respect to the sphere), rounded once
/// (nearly). Near the surface |f|^2 and r^2 agree in their leading digits: a ray 1 above a sphere
/// of radius 1e4 has c = 2e4 next to |f|^2 = 1e8, and |f|^2 rounded to float alone would move c
/// by 4. Exact squares, compensated sums (dot_compensated), and the first-order term 2 f . f_lo.
template <typename T>
inline T constant_term(Vec3Of<T> f, Vec3Of<T> f_lo, T r) {
    T ff_lo, rr_lo, e_c;
    const T ff = dot_compensated(f, f, ff_lo);
    const T rr = two_product(r, r, rr_lo);
    const T hi = two_sum(ff, -rr, e_c);
    return hi + ((e_c + (ff_lo - rr_lo)) + T(2) * glm::dot(f, f_lo));
}

/// The discriminant b^2 - a c as a (r^2 - |l|^2), l = f - (b / a) d the perpendicular offset of
/// the centre from the ray's line (Haines et al.): its error is ulps of a r |f| where b^2 - a c
/// has ulps of a |f|^2, for far and for tiny spheres. (a = 0 or a NaN input gives NaN.)
template <typename T>
inline T perpendicular_discriminant(Vec3Of<T> f, Vec3Of<T> d, T a, T b, T r2) {
    const Vec3Of<T> l = f - (b / a) * d;
    return a * (r2 - glm::dot(l, l));
}

// ---- intersection ------------------------------------------------------------------------------

/// Nearest t in the open interval (ray.t_min, ray.t_max) where the ray meets the sphere, or
/// infinity. The far root is returned when the origin is inside. dir need not be unit length.
/// T is the real type the arithmetic runs in (the sphere's float fields are converted to it).
/// Haines, Guenther, Akenine-Moeller, "Precision Improvements for Ray/Sphere Intersection",
/// Ray Tracing Gems ch. 7 (2019): the discriminant from the perpendicular offset of the centre
/// away from the sphere, and the roots from the cancellation-free formula. Near the sphere b and
/// c are carried past float's rounding, so that the near root c / q of a ray from just above a
/// large sphere keeps its digits too (numerics.md §4).
template <typename T>
inline T intersect_sphere(const Sphere& s, const RayOf<T>& ray) {
    // quadratic a t^2 + 2 b t + c = 0 with f = org - center
    const Vec3Of<T> f = ray.org - Vec3Of<T>(s.center);
    const Vec3Of<T> d = ray.dir;
    const T r = static_cast<T>(s.radius);
    const T r2 = r * r;
    const T a = glm::dot(d, d);
    T b = glm::dot(f, d);
    T c = glm::dot(f, f) - r2;

    // discriminant b^2 - a c. Near the sphere (c < r^2: |f|^2 < 2 r^2, and every origin inside)
    // b and c are recomputed past float's rounding and it is taken as written: b^2 and a c are
    // at most about 2 a r^2, and about 2 a r h for a ray from height h at a grazing angle, so its
    // error is ulps of that. Farther out, Haines et al.'s form. (a = 0 gives roots of infinity
    // and NaN, a NaN input a NaN discriminant: both fail the positive tests.)
    T disc;
    if (c < r2) {
        const Vec3Of<T> f_lo = center_offset_error(s, ray);
        b = half_linear_term(f, f_lo, d);
        c = constant_term(f, f_lo, r);
        disc = b * b - a * c;
    } else {
        disc = perpendicular_discriminant(f, d, a, b, r2);
    }
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
