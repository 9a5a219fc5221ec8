// traverse: ray/box (axis-aligned box primitive) intersection, the reference path (one ray,
// object space). Mirrored by box_packet.h.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/ray.h"
#include "scene/scene.h"
#include "traverse/local_geometry.h"
#include "traverse/slab_scalar.h"

namespace raylane {

/// Nearest t in the open interval (ray.t_min, ray.t_max) where the ray meets the box, or
/// infinity; the exit t when the origin is inside. The slab test of slab_scalar.h with the
/// same conventions (far distance scaled by slab_far_scale for the decision, so a box of zero
/// thickness crossed by the ray is hit; closed test; a ray lying in a face plane counts as
/// inside that slab), except that NaN inputs and rays lying in a zero-thickness slab miss.
/// T is the real type the arithmetic runs in.
template <typename T>
inline T intersect_box(const Box& b, const RayOf<T>& ray) {
    const T inf = infinity_of<T>;
    const Vec3Of<T> lo(b.lo), hi(b.hi);
    const Vec3Of<T> inv_dir(T(1) / ray.dir.x, T(1) / ray.dir.y, T(1) / ray.dir.z);
    T t_enter = -inf;
    T t_exit = inf;
    for (int i = 0; i < 3; ++i) {
        // slab i: near/far by the sign of inv_dir (-0.0 gives -inf)
        const T t_lo = (lo[i] - ray.org[i]) * inv_dir[i];
        const T t_hi = (hi[i] - ray.org[i]) * inv_dir[i];
        const bool neg = inv_dir[i] < T(0);
        const T t_near = neg ? t_hi : t_lo;
        const T t_far = neg ? t_lo : t_hi;

        // NaN: for one plane only (0 * inf, the ray lies in that face plane) the slab stays open
        // on that side; for both planes (a NaN input, or the ray lies in a slab of zero
        // thickness) the box is missed
        if (!(t_lo == t_lo || t_hi == t_hi)) return inf;

        // interval: NaN-safe updates (a NaN leaves the bound unchanged)
        t_enter = t_near > t_enter ? t_near : t_enter;
        t_exit = t_far < t_exit ? t_far : t_exit;
    }
    // decide: closed test against the inflated exit (Ize 2013)
    if (!(t_enter <= t_exit * slab_far_scale_of<T>)) return inf;

    // accept: the entry, or the exit when the entry is not after t_min (origin inside)
    if (t_enter > ray.t_min && t_enter < ray.t_max) return t_enter;
    if (t_exit > ray.t_min && t_exit < ray.t_max) return t_exit;
    return inf;
}

/// The renderer's test: intersect_box in float.
inline float intersect_box(const Box& b, const Ray& ray) {
    return intersect_box<float>(b, ray_of<float>(ray));
}

/// Normal and uv at an object-space point p on the box. The face is the one whose plane is
/// nearest to p; ties (edges, corners, zero thickness) go to x before y before z, and to the lo
/// face before the hi face. uv are p's coordinates on the face along the next two axes in cyclic
/// order (x: y, z; y: z, x; z: x, y), scaled to [0, 1] (0 along an axis of zero extent).
template <typename T>
inline LocalGeometryOf<T> geometry_box(const Box& b, Vec3Of<T> p) {
    const Vec3Of<T> lo(b.lo), hi(b.hi);
    // face: nearest plane, strict < keeps the earlier axis on ties
    int axis = 0;
    T side = T(-1);
    T best = infinity_of<T>;
    for (int i = 0; i < 3; ++i) {
        const T d_lo = std::abs(p[i] - lo[i]);
        const T d_hi = std::abs(p[i] - hi[i]);
        const T d = d_lo <= d_hi ? d_lo : d_hi;
        if (d < best) {
            best = d;
            axis = i;
            side = d_lo <= d_hi ? T(-1) : T(1);
        }
    }
    LocalGeometryOf<T> g;
    g.normal = Vec3Of<T>(T(0));
    g.normal[axis] = side;

    // uv: position on the face
    const int iu = (axis + 1) % 3;
    const int iv = (axis + 2) % 3;
    const Vec3Of<T> extent = hi - lo;
    const T u = extent[iu] > T(0) ? (p[iu] - lo[iu]) / extent[iu] : T(0);
    const T v = extent[iv] > T(0) ? (p[iv] - lo[iv]) / extent[iv] : T(0);
    g.uv = glm::vec<2, T>(std::clamp(u, T(0), T(1)), std::clamp(v, T(0), T(1)));
    return g;
}

}  // namespace raylane
