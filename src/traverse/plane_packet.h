// traverse: ray/plane intersection (infinite plane, kept outside the BVH), W rays against one
// plane (the packet path, object space). Mirrors plane_scalar.h step by step: a lane's t is
// bit-identical to the scalar result.
#pragma once

#include "core/ray_packet.h"
#include "scene/scene.h"
#include "traverse/plane_scalar.h"

namespace raylane::RAYLANE_ISA_NS {

/// Per lane, t in the open interval (t_min, t_max) where the ray meets the plane, or infinity
/// (misses and inactive lanes). A ray parallel to the plane divides by zero (+-inf, or NaN when
/// it lies in the plane); the positive acceptance test rejects both.
template <int W>
inline vfloat<W> intersect_plane(const Plane& p, const RayPacket<W>& rays, vmask<W> active) {
    const vfloat<W> inf(infinity);
    if (none(active)) return inf;

    // distance: t = n.(point - org) / n.dir
    const Vec3<W> n = make_vec3<W>(p.normal.x, p.normal.y, p.normal.z);
    const Vec3<W> to_point = make_vec3<W>(p.point.x, p.point.y, p.point.z) - rays.org;
    const vfloat<W> t = dot<W>(n, to_point) / dot<W>(n, rays.dir);
    // accept
    const vmask<W> hit = mask_and(mask_and(t > rays.t_min, t < rays.t_max), active);
    return select(hit, t, inf);
}

}  // namespace raylane::RAYLANE_ISA_NS
