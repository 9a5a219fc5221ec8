// shade: Fresnel reflectance, mirror and refracted directions, and Beer's law for W shading
// points. Mirrors optics_scalar.h: same names, same order, same operation order, so W = 1 matches
// the scalar path bit for bit (Beer's law uses xsimd's exp at wider W: a few ulps).
#pragma once

#include <cmath>

#include "shade/brdf_packet.h"  // brdf_detail::exp: the same exp as the lobes
#include "shade/optics_scalar.h"
#include "simd/lanes.h"
#include "simd/math.h"
#include "simd/simd.h"
#include "simd/vec3.h"

namespace raylane::RAYLANE_ISA_NS {

namespace optics_detail {

template <int W>
inline vfloat<W> transmitted_cos2(const vfloat<W>& ci, const vfloat<W>& eta) {
    return ((eta - 1.0f) * (eta + 1.0f) + ci * ci) / (eta * eta);
}

}  // namespace optics_detail

template <int W>
inline vfloat<W> schlick(const vfloat<W>& r0, const vfloat<W>& cos_theta) {
    const vfloat<W> c = min(max(cos_theta, vfloat<W>(0.0f)), vfloat<W>(1.0f));
    const vfloat<W> m = 1.0f - c;
    const vfloat<W> m2 = m * m;
    return r0 + (1.0f - r0) * (m2 * m2 * m);
}

template <int W>
inline vfloat<W> fresnel_dielectric(const vfloat<W>& cos_i, const vfloat<W>& eta,
                                    const vfloat<W>& cos_t) {
    const vfloat<W> zero(0.0f), one(1.0f);
    const vfloat<W> ci = min(max(cos_i, zero), one);
    const vfloat<W> ct = min(max(cos_t, zero), one);
    const vfloat<W> r_par = (eta * ci - ct) / (eta * ci + ct);
    const vfloat<W> r_perp = (ci - eta * ct) / (ci + eta * ct);
    const vfloat<W> r = 0.5f * (r_par * r_par + r_perp * r_perp);
    return select(ci > zero, r, one);
}

template <int W>
inline vfloat<W> fresnel_dielectric(const vfloat<W>& cos_i, const vfloat<W>& eta) {
    const vfloat<W> zero(0.0f), one(1.0f);
    const vfloat<W> ci = min(max(cos_i, zero), one);
    const vfloat<W> cos2_t = optics_detail::transmitted_cos2<W>(ci, eta);
    const vfloat<W> cos_t = select(eta == one, ci, sqrt(max(cos2_t, zero)));
    // index-matched (eta 1): no interface, R = 0 even where 1 - cos^2 rounds to 1
    return select(mask_or(cos2_t > zero, eta == one), fresnel_dielectric<W>(ci, eta, cos_t), one);
}

template <int W>
inline Vec3<W> reflect_direction(const Vec3<W>& d, const Vec3<W>& n) {
    return d - n * (2.0f * dot(d, n));
}

/// Returns the lanes that refract (false = total internal reflection: t = mirror, cos_t = 0).
template <int W>
inline vmask<W> refract_direction(const Vec3<W>& d, const Vec3<W>& n_facing, const vfloat<W>& eta,
                                  Vec3<W>& t, vfloat<W>& cos_t) {
    const vfloat<W> zero(0.0f), one(1.0f);
    const vfloat<W> ci = min(max(neg(dot(d, n_facing)), zero), one);
    const vmask<W> unit = eta == one;
    const vfloat<W> cos2_t = optics_detail::transmitted_cos2<W>(ci, eta);
    const vmask<W> refracts = cos2_t > zero;
    const vfloat<W> ct = sqrt(max(cos2_t, zero));
    const Vec3<W> refracted = d / eta - n_facing * (ct - ci / eta);
    t = select(unit, d, select(refracts, refracted, reflect_direction(d, n_facing)));
    cos_t = select(unit, ci, select(refracts, ct, zero));
    return mask_or(unit, refracts);
}

namespace optics_detail {
template <int W>
inline vfloat<W> beer_channel(float filter, const vfloat<W>& distance) {
    const vfloat<W> zero(0.0f), one(1.0f);
    if (!(filter < 1.0f)) return one;
    if (!(filter > 0.0f)) return select(distance > zero, zero, one);
    return select(distance > zero, brdf_detail::exp<W>(distance * std::log(filter)), one);
}
}  // namespace optics_detail

/// filter shared by all lanes (a material's), distance per lane.
template <int W>
inline Vec3<W> beer_transmittance(vec3 filter, const vfloat<W>& distance) {
    using namespace optics_detail;
    return {beer_channel<W>(filter.x, distance), beer_channel<W>(filter.y, distance),
            beer_channel<W>(filter.z, distance)};
}

}  // namespace raylane::RAYLANE_ISA_NS
