// core: spawning secondary rays without self-intersection, W at a time. Mirrors offset.h:
// the same integer steps on the float bits, so each lane equals the scalar result bit for bit.
// Waechter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection", RT Gems ch. 6.
#pragma once

#include "core/offset.h"
#include "simd/math.h"
#include "simd/vec3.h"

namespace raylane {

template <int W>
inline Vec3<W> offset_ray_origin(const Vec3<W>& p, const Vec3<W>& n) {
    auto axis = [](const vfloat<W>& pk, const vfloat<W>& nk) {
        const vint<W> of_i = to_int(vfloat<W>(offset_int_scale) * nk);  // truncates, as the cast
        const vint<W> bits_p = float_as_int(pk);
        const vmask<W> negative = pk < vfloat<W>(0.0f);
        const vint<W> moved = select(negative, bits_p - of_i, bits_p + of_i);
        const vfloat<W> p_i = int_as_float(moved);
        const vfloat<W> p_f = pk + vfloat<W>(offset_float_scale) * nk;
        return select(abs(pk) < vfloat<W>(offset_origin), p_f, p_i);
    };
    return {axis(p.x, n.x), axis(p.y, n.y), axis(p.z, n.z)};
}

}  // namespace raylane
