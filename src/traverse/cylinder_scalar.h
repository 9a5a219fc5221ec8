// traverse: ray/cylinder intersection (finite, capped, around +y), the reference path (one ray,
// object space). Mirrored by cylinder_packet.h.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/ray.h"
#include "scene/scene.h"
#include "traverse/local_geometry.h"

namespace raylane {

/// Nearest t in the open interval (ray.t_min, ray.t_max) where the ray meets the cylinder
/// x^2 + z^2 <= r^2, 0 <= y <= h (side and both caps), or infinity; the exit t when the origin
/// is inside. The side is intersected only when a = dx^2 + dz^2 > 0.
///
/// Both predicates are closed and written as t-intervals: a side root is kept when it lies in
/// the cap slab's interval (0 <= y <= h), a cap hit when it lies in the side's interval
/// (x^2 + z^2 <= r^2). The two decisions at a rim then compare the same rounded numbers, so a
/// ray the intervals say crosses the solid is always accepted by one of them: no leak at the
/// rims (numerics.md §5). Side roots as for spheres (Haines, Guenther, Akenine-Moeller, Ray
/// Tracing Gems ch. 7, 2019), in the xz plane. T is the real type the arithmetic runs in.
template <typename T>
inline T intersect_cylinder(const Cylinder& cyl, const RayOf<T>& ray) {
    const Vec3Of<T> o = ray.org;
    const Vec3Of<T> d = ray.dir;
    const T r2 = static_cast<T>(cyl.radius) * static_cast<T>(cyl.radius);
    const T inf = infinity_of<T>;

    // side: the infinite cylinder as the interval [s_lo, s_hi] of t (a t^2 + 2 b t + c = 0)
    const T a = d.x * d.x + d.z * d.z;
    const T b = o.x * d.x + o.z * d.z;
    const T c = o.x * o.x + o.z * o.z - r2;
    T s_lo = -inf;
    T s_hi = inf;
    if (a > T(0)) {
        // discriminant from the perpendicular offset of the axis: b^2 - a c = a (r^2 - |l|^2)
        const T lx = o.x - (b / a) * d.x;
        const T lz = o.z - (b / a) * d.z;
        const T disc = a * (r2 - (lx * lx + lz * lz));
        if (!(disc >= T(0))) return inf;
        const T q = -(b + std::copysign(std::sqrt(disc), b));
        const T t0 = c / q;
        const T t1 = q / a;
        s_lo = t0 < t1 ? t0 : t1;
        s_hi = t0 < t1 ? t1 : t0;
    } else if (!(c <= T(0))) {
        return inf;  // parallel to the axis (or NaN), outside the closed disc
    }

    // caps: the slab 0 <= y <= h as the interval [y_lo, y_hi] of t, near/far by the sign bit of
    // dy. A NaN distance for one plane (0 / 0, the ray lies in that cap plane) leaves that end
    // open; for both (a NaN input, or height 0) the cylinder is missed
    const T t_bottom = (T(0) - o.y) / d.y;
    const T t_top = (static_cast<T>(cyl.height) - o.y) / d.y;
    if (!(t_bottom == t_bottom || t_top == t_top)) return inf;
    const bool down = std::signbit(d.y);
    const T y_near = down ? t_top : t_bottom;
    const T y_far = down ? t_bottom : t_top;
    const T y_lo = y_near > -inf ? y_near : -inf;
    const T y_hi = y_far < inf ? y_far : inf;

    // accept: smallest candidate in (t_min, t_max) lying in the other interval (closed)
    T t = inf;
    if (a > T(0)) {
        if (s_lo >= y_lo && s_lo <= y_hi && s_lo > ray.t_min && s_lo < ray.t_max && s_lo < t)
            t = s_lo;
        if (s_hi >= y_lo && s_hi <= y_hi && s_hi > ray.t_min && s_hi < ray.t_max && s_hi < t)
            t = s_hi;
    }
    if (y_lo >= s_lo && y_lo <= s_hi && y_lo > ray.t_min && y_lo < ray.t_max && y_lo < t) t = y_lo;
    if (y_hi >= s_lo && y_hi <= s_hi && y_hi > ray.t_min && y_hi < ray.t_max && y_hi < t) t = y_hi;
    return t;
}

/// The renderer's test: intersect_cylinder in float.
inline float intersect_cylinder(const Cylinder& cyl, const Ray& ray) {
    return intersect_cylinder<float>(cyl, ray_of<float>(ray));
}

/// Normal and uv at an object-space point p on the cylinder. The part is the one nearest to p
/// (side, bottom cap, top cap; ties go in that order). Side: normal (x, 0, z) / |(x, z)|,
/// uv = (phi / 2 pi, y / h). Caps: normal -y or +y, uv = (phi / 2 pi, |(x, z)| / r). phi is the
/// azimuth around +y from +x towards +z. With with_uv false, uv stays 0 (no atan2; see
/// geometry_sphere).
template <typename T>
inline LocalGeometryOf<T> geometry_cylinder(const Cylinder& cyl, Vec3Of<T> p, bool with_uv = true) {
    const T radius = static_cast<T>(cyl.radius);
    const T height = static_cast<T>(cyl.height);
    const T rho = std::sqrt(p.x * p.x + p.z * p.z);
    const T d_side = std::abs(rho - radius);
    const T d_bottom = std::abs(p.y);
    const T d_top = std::abs(p.y - height);
    LocalGeometryOf<T> g;
    const T u = with_uv ? azimuth_fraction(p.x, p.z) : T(0);
    if (d_side <= d_bottom && d_side <= d_top) {
        // side (on the axis only for a zero radius: any horizontal normal will do)
        g.normal = rho > T(0) ? Vec3Of<T>(p.x / rho, T(0), p.z / rho) : Vec3Of<T>(T(1), T(0), T(0));
        const T v = height > T(0) ? p.y / height : T(0);
        if (with_uv) g.uv = glm::vec<2, T>(u, std::clamp(v, T(0), T(1)));
    } else {
        // caps
        g.normal = d_bottom <= d_top ? Vec3Of<T>(T(0), T(-1), T(0)) : Vec3Of<T>(T(0), T(1), T(0));
        const T v = radius > T(0) ? rho / radius : T(0);
        if (with_uv) g.uv = glm::vec<2, T>(u, std::clamp(v, T(0), T(1)));
    }
    return g;
}

}  // namespace raylane
