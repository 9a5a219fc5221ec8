// core: spawning secondary rays without self-intersection, W at a time. Mirrors offset.h:
// the same integer steps on the float bits, so each lane equals the scalar result bit for bit.
// Waechter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection", RT Gems ch. 6.
#pragma once

#include "core/offset.h"
#include "core/ray_packet.h"
#include "simd/math.h"
#include "simd/vec3.h"

namespace raylane::RAYLANE_ISA_NS {

/// ray_reach, lane-wise.
template <int W>
inline vfloat<W> ray_reach(const RayPacket<W>& rays, const vfloat<W>& t) {
    const vfloat<W> o = max(max(abs(rays.org.x), abs(rays.org.y)), abs(rays.org.z));
    const vfloat<W> d = max(max(abs(rays.dir.x), abs(rays.dir.y)), abs(rays.dir.z));
    return o + t * d;
}

template <int W>
inline Vec3<W> offset_ray_origin(const Vec3<W>& p, const Vec3<W>& n, const vfloat<W>& reach) {
    const vfloat<W> near_zero = vfloat<W>(offset_origin) * reach;
    const vfloat<W> step = vfloat<W>(offset_float_scale) * reach;
    auto axis = [&](const vfloat<W>& pk, const vfloat<W>& nk) {
        const vfloat<W> scaled = vfloat<W>(offset_int_scale) * nk;
        // truncates, as the cast; a NaN normal moves nothing
        const vint<W> of_i = select(scaled == scaled, to_int(scaled), vint<W>(0));
        const vint<W> bits_p = float_as_int(pk);
        const vmask<W> negative = pk < vfloat<W>(0.0f);
        const vint<W> moved = select(negative, bits_p - of_i, bits_p + of_i);
        const vfloat<W> p_i = int_as_float(moved);
        const vfloat<W> p_f = pk + step * nk;
        return select(abs(pk) < near_zero, p_f, p_i);
    };
    return {axis(p.x, n.x), axis(p.y, n.y), axis(p.z, n.z)};
}

}  // namespace raylane::RAYLANE_ISA_NS
