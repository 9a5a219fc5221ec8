// traverse: watertight ray/triangle intersection, the reference path (one ray).
// Mirrored by triangle_packet.h.
// Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013.
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include "core/ray.h"
#include "core/triangle_area.h"
#include "traverse/local_geometry.h"

namespace raylane {

/// A ray prepared for the watertight test: after translating by org, permuting the axes to
/// (kx, ky, kz) and shearing with (sx, sy, sz), the ray is the +z axis.
template <typename T>
struct WatertightRayOf {
    Vec3Of<T> org{T(0)};
    Vec3Of<T> dir{T(0), T(0), T(1)};  ///< the ray's own direction (plane_distance_in_double)
    int kx = 0, ky = 1, kz = 2;
    T sx = T(0), sy = T(0), sz = T(1);
};
using WatertightRay = WatertightRayOf<float>;

/// kz is the axis of the largest |dir| component (ties to the lower axis), kx and ky follow it
/// cyclically and are swapped when dir[kz] < 0 so the winding is kept. sx = d[kx] / d[kz],
/// sy = d[ky] / d[kz], sz = 1 / d[kz], by division.
template <typename T>
inline WatertightRayOf<T> make_watertight_ray(const RayOf<T>& ray) {
    WatertightRayOf<T> wr;
    wr.org = ray.org;
    wr.dir = ray.dir;
    const Vec3Of<T> ad = glm::abs(ray.dir);
    wr.kz = ad.x >= ad.y ? (ad.x >= ad.z ? 0 : 2) : (ad.y >= ad.z ? 1 : 2);
    wr.kx = (wr.kz + 1) % 3;
    wr.ky = (wr.kx + 1) % 3;
    if (ray.dir[wr.kz] < T(0)) std::swap(wr.kx, wr.ky);
    wr.sx = ray.dir[wr.kx] / ray.dir[wr.kz];
    wr.sy = ray.dir[wr.ky] / ray.dir[wr.kz];
    wr.sz = T(1) / ray.dir[wr.kz];
    return wr;
}
inline WatertightRay make_watertight_ray(const Ray& ray) {
    return make_watertight_ray<float>(ray_of<float>(ray));
}

/// x y - z w to within 2 units of roundoff of the exact value, so with its sign and exactly 0 only
/// when it is 0 (barring underflow): W. Kahan's difference of products, the error of z w
/// recovered with an FMA (Jeannerod, Louvet, Muller, "Further analysis of Kahan's algorithm for
/// the accurate computation of 2x2 determinants", Math. Comp. 2013). The edge-function fallback
/// of the double instantiation, where products of two doubles are not exact.
inline double difference_of_products(double x, double y, double z, double w) {
    const double zw = z * w;
    const double err = std::fma(-z, w, zw);
    return std::fma(x, y, -zw) + err;
}

/// The distance along d from o to the plane of (a, b, c), dot(a - o, n) / dot(d, n) with
/// n = cross(b - a, c - a), in double: for rays whose float t loses its bits to cancellation.
/// Shared by both paths.
inline float plane_distance_in_double(vec3 o, vec3 d, vec3 a, vec3 b, vec3 c) {
    const glm::dvec3 da(a);
    const glm::dvec3 n = glm::cross(glm::dvec3(b) - da, glm::dvec3(c) - da);
    return static_cast<float>(glm::dot(da - glm::dvec3(o), n) / glm::dot(glm::dvec3(d), n));
}

/// True when the ray hits triangle (a, b, c) from either side at t in the open interval
/// (t_min, t_max); then t, and u, v = the barycentric weights of b and c, are written (outputs
/// are left alone on a miss). A ray through a shared edge or vertex hits at least one of the
/// triangles sharing it (an edge function of zero counts as inside). Zero-area triangles and
/// NaN inputs never hit. Requires -ffp-contract=off: see numerics.md §1. T is the real type the
/// arithmetic runs in; the zero fallback is exact for float (double products) and sign-exact
/// for double (difference_of_products).
template <typename T>
inline bool intersect_triangle(const WatertightRayOf<T>& wr, Vec3Of<T> a, Vec3Of<T> b, Vec3Of<T> c,
                               T t_min, T t_max, T& t, T& u, T& v) {
    // translate: vertices relative to the ray origin
    const Vec3Of<T> A = a - wr.org;
    const Vec3Of<T> B = b - wr.org;
    const Vec3Of<T> C = c - wr.org;

    // shear: the ray becomes the +z axis (z is scaled later, for candidates only)
    const T ax = A[wr.kx] - wr.sx * A[wr.kz];
    const T ay = A[wr.ky] - wr.sy * A[wr.kz];
    const T bx = B[wr.kx] - wr.sx * B[wr.kz];
    const T by = B[wr.ky] - wr.sy * B[wr.kz];
    const T cx = C[wr.kx] - wr.sx * C[wr.kz];
    const T cy = C[wr.ky] - wr.sy * C[wr.kz];

    // edge functions: e_a, e_b, e_c are det times the weights of a, b, c; the function of an
    // edge shared by two triangles is the same expression of the same two sheared vertices
    T e_a = cx * by - cy * bx;
    T e_b = ax * cy - ay * cx;
    T e_c = bx * ay - by * ax;

    // fallback: an exactly zero edge function is recomputed in double, where the products of
    // two floats are exact, so its sign is right (the double instantiation: Kahan's difference
    // of products, whose sign is exact too)
    if (e_a == T(0) || e_b == T(0) || e_c == T(0)) {
        if constexpr (std::is_same_v<T, float>) {
            e_a = static_cast<float>(double(cx) * double(by) - double(cy) * double(bx));
            e_b = static_cast<float>(double(ax) * double(cy) - double(ay) * double(cx));
            e_c = static_cast<float>(double(bx) * double(ay) - double(by) * double(ax));
        } else {
            e_a = static_cast<T>(difference_of_products(cx, by, cy, bx));
            e_b = static_cast<T>(difference_of_products(ax, cy, ay, cx));
            e_c = static_cast<T>(difference_of_products(bx, ay, by, ax));
        }
    }

    // inside: no edge function negative, or none positive (positive form: NaN is outside)
    const bool inside =
        (e_a >= T(0) && e_b >= T(0) && e_c >= T(0)) || (e_a <= T(0) && e_b <= T(0) && e_c <= T(0));
    if (!inside) return false;
    const T det = e_a + e_b + e_c;
    if (det == T(0)) return false;

    // degenerate: zero-area triangles (the shear may round collinear vertices apart)
    if (is_zero_area_triangle(a, b, c)) return false;

    // distance: t_scaled = t det, tested against the interval scaled by |det| (no division yet)
    const T az = wr.sz * A[wr.kz];
    const T bz = wr.sz * B[wr.kz];
    const T cz = wr.sz * C[wr.kz];
    const T t_scaled = e_a * az + e_b * bz + e_c * cz;
    const T det_sign = std::copysign(T(1), det);
    const T abs_det = det_sign * det;
    const T t_signed = det_sign * t_scaled;
    if constexpr (std::is_same_v<T, float>) {
        // cancellation: the origin lies between the vertices' depths (a surface close to the
        // origin, far vertices), so t_scaled is a small difference of larger terms and may be
        // hundreds of ulps off; two coplanar triangles would then disagree on t, and the
        // tie-break with them. Unless t is surely outside the interval (t_scaled is within
        // 2^-10 of the terms of its exact value, a wide margin over a few roundings), t comes
        // from the plane in double (numerics.md section 2).
        const float terms = std::fabs(e_a * az) + std::fabs(e_b * bz) + std::fabs(e_c * cz);
        if (terms > 2.0f * std::fabs(t_scaled)) {
            const float slack = terms * 0x1.0p-10f;
            if (t_signed + slack < t_min * abs_det || t_signed - slack > t_max * abs_det)
                return false;
            const float t_plane = plane_distance_in_double(wr.org, wr.dir, a, b, c);
            if (!(t_plane > t_min && t_plane < t_max)) return false;
            t = t_plane;
            u = e_b / det;
            v = e_c / det;
            return true;
        }
    }
    if (!(t_signed > t_min * abs_det && t_signed < t_max * abs_det)) return false;

    // divide: only now, and re-check so rounding cannot leave the open interval
    const T t_hit = t_scaled / det;
    if (!(t_hit > t_min && t_hit < t_max)) return false;
    t = t_hit;
    u = e_b / det;
    v = e_c / det;
    return true;
}

/// False when |n|^2 of a float cross product is not a normal finite float: a sliver or a tiny
/// triangle (below FLT_MIN, or flushed to zero under FTZ) or a huge one, whose float normalize
/// gives NaN or a wrong length (numerics.md section 8).
inline bool float_normal_is_safe(float length2) {
    return length2 >= std::numeric_limits<float>::min() &&
           length2 <= std::numeric_limits<float>::max();
}

/// The unit normal computed in double from double edges, for the triangles float_normal_is_safe
/// rejects. Shared by both paths.
inline vec3 triangle_normal_in_double(vec3 a, vec3 b, vec3 c) {
    const glm::dvec3 da(a);
    return vec3(glm::normalize(glm::cross(glm::dvec3(b) - da, glm::dvec3(c) - da)));
}

/// Normal and uv at a hit: normal = normalize(cross(b - a, c - a)), the side the winding
/// (a, b, c) gives (in double when float would underflow or overflow), and uv = (u, v) the
/// barycentric weights of b and c.
template <typename T>
inline LocalGeometryOf<T> geometry_triangle(Vec3Of<T> a, Vec3Of<T> b, Vec3Of<T> c, T u, T v) {
    LocalGeometryOf<T> g;
    const Vec3Of<T> n = glm::cross(b - a, c - a);
    g.normal = glm::normalize(n);
    if constexpr (std::is_same_v<T, float>) {
        if (!float_normal_is_safe(glm::dot(n, n))) g.normal = triangle_normal_in_double(a, b, c);
    }
    g.uv = glm::vec<2, T>(u, v);
    return g;
}

}  // namespace raylane
