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
/// Tracing Gems ch. 7, 2019), in the xz plane.
inline float intersect_cylinder(const Cylinder& cyl, const Ray& ray) {
    const vec3 o = ray.org;
    const vec3 d = ray.dir;
    const float r2 = cyl.radius * cyl.radius;

    // side: the infinite cylinder as the interval [s_lo, s_hi] of t (a t^2 + 2 b t + c = 0)
    const float a = d.x * d.x + d.z * d.z;
    const float b = o.x * d.x + o.z * d.z;
    const float c = o.x * o.x + o.z * o.z - r2;
    float s_lo = -infinity;
    float s_hi = infinity;
    if (a > 0.0f) {
        // discriminant from the perpendicular offset of the axis: b^2 - a c = a (r^2 - |l|^2)
        const float lx = o.x - (b / a) * d.x;
        const float lz = o.z - (b / a) * d.z;
        const float disc = a * (r2 - (lx * lx + lz * lz));
        if (!(disc >= 0.0f)) return infinity;
        const float q = -(b + std::copysign(std::sqrt(disc), b));
        const float t0 = c / q;
        const float t1 = q / a;
        s_lo = t0 < t1 ? t0 : t1;
        s_hi = t0 < t1 ? t1 : t0;
    } else if (!(c <= 0.0f)) {
        return infinity;  // parallel to the axis (or NaN), outside the closed disc
    }

    // caps: the slab 0 <= y <= h as the interval [y_lo, y_hi] of t, near/far by the sign bit of
    // dy. A NaN distance for one plane (0 / 0, the ray lies in that cap plane) leaves that end
    // open; for both (a NaN input, or height 0) the cylinder is missed
    const float t_bottom = (0.0f - o.y) / d.y;
    const float t_top = (cyl.height - o.y) / d.y;
    if (!(t_bottom == t_bottom || t_top == t_top)) return infinity;
    const bool down = std::signbit(d.y);
    const float y_near = down ? t_top : t_bottom;
    const float y_far = down ? t_bottom : t_top;
    const float y_lo = y_near > -infinity ? y_near : -infinity;
    const float y_hi = y_far < infinity ? y_far : infinity;

    // accept: smallest candidate in (t_min, t_max) lying in the other interval (closed)
    float t = infinity;
    if (a > 0.0f) {
        if (s_lo >= y_lo && s_lo <= y_hi && s_lo > ray.t_min && s_lo < ray.t_max && s_lo < t)
            t = s_lo;
        if (s_hi >= y_lo && s_hi <= y_hi && s_hi > ray.t_min && s_hi < ray.t_max && s_hi < t)
            t = s_hi;
    }
    if (y_lo >= s_lo && y_lo <= s_hi && y_lo > ray.t_min && y_lo < ray.t_max && y_lo < t) t = y_lo;
    if (y_hi >= s_lo && y_hi <= s_hi && y_hi > ray.t_min && y_hi < ray.t_max && y_hi < t) t = y_hi;
    return t;
}

/// Normal and uv at an object-space point p on the cylinder. The part is the one nearest to p
/// (side, bottom cap, top cap; ties go in that order). Side: normal (x, 0, z) / |(x, z)|,
/// uv = (phi / 2 pi, y / h). Caps: normal -y or +y, uv = (phi / 2 pi, |(x, z)| / r). phi is the
/// azimuth around +y from +x towards +z.
inline LocalGeometry geometry_cylinder(const Cylinder& cyl, vec3 p) {
    const float rho = std::sqrt(p.x * p.x + p.z * p.z);
    const float d_side = std::abs(rho - cyl.radius);
    const float d_bottom = std::abs(p.y);
    const float d_top = std::abs(p.y - cyl.height);
    LocalGeometry g;
    const float u = azimuth_fraction(p.x, p.z);
    if (d_side <= d_bottom && d_side <= d_top) {
        // side (on the axis only for a zero radius: any horizontal normal will do)
        g.normal = rho > 0.0f ? vec3(p.x / rho, 0.0f, p.z / rho) : vec3(1.0f, 0.0f, 0.0f);
        const float v = cyl.height > 0.0f ? p.y / cyl.height : 0.0f;
        g.uv = vec2(u, std::clamp(v, 0.0f, 1.0f));
    } else {
        // caps
        g.normal = d_bottom <= d_top ? vec3(0.0f, -1.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
        const float v = cyl.radius > 0.0f ? rho / cyl.radius : 0.0f;
        g.uv = vec2(u, std::clamp(v, 0.0f, 1.0f));
    }
    return g;
}

}  // namespace raylane
