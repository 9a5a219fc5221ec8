// shade: BRDF lobes, shading factors and lobe sampling for W shading points that share one
// material (Fresnel, refraction and Beer's law: optics_packet.h). Mirrors brdf_scalar.h: same
// names, same order, same operation order, so W = 1 matches the scalar path bit for bit and wider
// packets differ only by the vector exp / log / log1p / expm1 / sin / cos of xsimd (a few ulps; see
// brdf_packet_test.cpp).
//
// Every function is lane-wise and pure: nothing is written to memory except the out-parameters,
// which get every lane. Lanes that fail a condition (ci <= 0, TIR, ...) get the same values as
// the scalar path; garbage in inactive lanes cannot trap. All lanes compute, except where a whole
// packet's result is known exactly without it (phong_lobe past phong_zero_chord2).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "shade/brdf_scalar.h"
#include "simd/lanes.h"
#include "simd/math.h"
#include "simd/simd.h"
#include "simd/vec3.h"

namespace raylane::RAYLANE_ISA_NS {

namespace brdf_detail {

// Transcendentals: the std:: functions (as brdf_scalar.cpp and optics_scalar.cpp) lane by lane
// at every W, so that every instruction set and both paths get the same bits. exp, log1p and
// expm1 are the lobes' own; cos and sin are simd/math.h's, named here by width.
template <int W>
inline vfloat<W> exp(const vfloat<W>& x) {
    return map_lanes(x, [](float v) { return std::exp(v); });
}
template <int W>
inline vfloat<W> log1p(const vfloat<W>& x) {
    return map_lanes(x, [](float v) { return std::log1p(v); });
}
template <int W>
inline vfloat<W> expm1(const vfloat<W>& x) {
    return map_lanes(x, [](float v) { return std::expm1(v); });
}
template <int W>
inline vfloat<W> cos(const vfloat<W>& x) {
    return ::raylane::RAYLANE_ISA_NS::cos(x);
}
template <int W>
inline vfloat<W> sin(const vfloat<W>& x) {
    return ::raylane::RAYLANE_ISA_NS::sin(x);
}

inline constexpr float pi = std::numbers::pi_v<float>;
inline constexpr float inv_pi = std::numbers::inv_pi_v<float>;
inline constexpr float two_pi = 2.0f * pi;
inline constexpr float four_pi = 4.0f * pi;
inline constexpr float inv_two_pi = 0.5f * inv_pi;

inline float clamp_exponent(float e) { return e > 0.0f ? e : 0.0f; }
inline float alpha_squared(float alpha) {
    const float a = alpha > brdf_alpha_min ? alpha : brdf_alpha_min;
    return a * a;
}

/// c * v for a vector shared by all lanes (c.x * v, ...), the order glm uses for vec3 * float.
template <int W>
inline Vec3<W> scale(vec3 c, const vfloat<W>& v) {
    return {c.x * v, c.y * v, c.z * v};
}

template <int W>
inline vfloat<W> half_tan2(const Vec3<W>& n, const Vec3<W>& h, const vfloat<W>& hz) {
    const Vec3<W> c = cross(n, h);
    return min(dot(c, c) / (hz * hz), vfloat<W>(brdf_tan2_max));
}

template <int W>
inline vfloat<W> ward_gaussian(const vfloat<W>& t2, float a2) {
    return exp<W>(neg(t2 / a2)) / (four_pi * a2);
}

template <int W>
inline Vec3<W> around_axis(const Vec3<W>& axis, const vfloat<W>& cos_t, const vfloat<W>& sin_t,
                           const vfloat<W>& phi);

template <int W>
inline vfloat<W> select0(const vmask<W>& m, const vfloat<W>& v) {
    return select(m, v, vfloat<W>(0.0f));
}

}  // namespace brdf_detail

/// Lane-wise LobeSample.
template <int W>
struct LobeSamplePacket {
    Vec3<W> wi;
    vfloat<W> pdf = vfloat<W>(0.0f);
    vfloat<W> weight = vfloat<W>(0.0f);
};

// ---- frames ---------------------------------------------------------------------------------

template <int W>
inline void orthonormal_basis(const Vec3<W>& n, Vec3<W>& t, Vec3<W>& b) {
    const vfloat<W> sign = copysign(vfloat<W>(1.0f), n.z);
    const vfloat<W> a = vfloat<W>(-1.0f) / (sign + n.z);
    const vfloat<W> c = n.x * n.y * a;
    t = {vfloat<W>(1.0f) + sign * n.x * n.x * a, sign * c, neg(sign) * n.x};
    b = {c, sign + n.y * n.y * a, neg(n.y)};
}

template <int W>
inline Vec3<W> mirror_direction(const Vec3<W>& n, const Vec3<W>& wo) {
    return n * (2.0f * dot(n, wo)) - wo;
}

template <int W>
inline Vec3<W> brdf_detail::around_axis(const Vec3<W>& axis, const vfloat<W>& cos_t,
                                        const vfloat<W>& sin_t, const vfloat<W>& phi) {
    Vec3<W> t, b;
    orthonormal_basis(axis, t, b);
    return t * (sin_t * cos<W>(phi)) + b * (sin_t * sin<W>(phi)) + axis * cos_t;
}

// ---- lobes ----------------------------------------------------------------------------------

/// The chord^2 from which phong_lobe's cos^e = exp(e ln cos) is below exp(-110), so exactly 0
/// in float: the smallest float is exp(-103.3), and xsimd's exp returns 0 below -88.4, so -110
/// leaves a margin of 6.7 for the rounding of log1p. That is 2 (1 - exp(-110 / e)), taken as
/// -2 expm1(-110 / e) (accurate for huge e too: 220 / e) and rounded up; 2 (the lobe's edge)
/// for e = 0; infinity (never skip) for an infinite e, where it would be 0. Recomputed when the
/// thread's exponent changes.
inline float phong_zero_chord2(float e) {
    thread_local float last_e = 0.0f, last = 2.0f;
    if (e != last_e) {
        const float c = static_cast<float>(-2.0 * std::expm1(-110.0 / static_cast<double>(e)));
        last = c >= std::numeric_limits<float>::min() ? std::min(std::nextafter(c, 4.0f), 2.0f)
                                                      : std::numeric_limits<float>::infinity();
        last_e = e;
    }
    return last;
}

template <int W>
inline vfloat<W> phong_lobe(const Vec3<W>& axis, const Vec3<W>& w, float e) {
    using namespace brdf_detail;
    const Vec3<W> d = w - axis;
    const vfloat<W> chord2 = dot(d, d);
    // every lane that far from the mirror direction: the lobe is 0 without exp and log1p
    const float exponent = clamp_exponent(e);
    if (none(chord2 < vfloat<W>(phong_zero_chord2(exponent)))) return vfloat<W>(0.0f);
    const vfloat<W> p = exp<W>(exponent * log1p<W>(-0.5f * chord2));
    return select0<W>(chord2 < vfloat<W>(2.0f), p);
}

template <int W>
inline vfloat<W> blinn_phong_lobe(const Vec3<W>& n, const Vec3<W>& wi, const Vec3<W>& wo,
                                  float exponent) {
    using namespace brdf_detail;
    const vfloat<W> ci = dot(n, wi), co = dot(n, wo), zero(0.0f);
    const float e = clamp_exponent(exponent);
    const vfloat<W> t2 = half_tan2(n, wi + wo, ci + co);
    const vfloat<W> s = ((e + 2.0f) * inv_two_pi) * exp<W>((-0.5f * e) * log1p<W>(t2));
    return select0<W>(mask_and(ci > zero, co > zero), s);
}

template <int W>
inline vfloat<W> ward_lobe(const Vec3<W>& n, const Vec3<W>& wi, const Vec3<W>& wo, float alpha) {
    using namespace brdf_detail;
    const vfloat<W> ci = dot(n, wi), co = dot(n, wo), zero(0.0f);
    const float a2 = alpha_squared(alpha);
    const vfloat<W> t2 = half_tan2(n, wi + wo, ci + co);
    const vfloat<W> lo = min(ci, co), hi = max(ci, co);
    const vfloat<W> s = ward_gaussian<W>(t2, a2) / sqrt(lo) / sqrt(hi);
    return select0<W>(mask_and(ci > zero, co > zero), min(s, vfloat<W>(brdf_lobe_max)));
}

template <int W>
inline vfloat<W> ward_duer_lobe(const Vec3<W>& n, const Vec3<W>& wi, const Vec3<W>& wo,
                                float alpha) {
    using namespace brdf_detail;
    const vfloat<W> ci = dot(n, wi), co = dot(n, wo), zero(0.0f);
    const float a2 = alpha_squared(alpha);
    const vfloat<W> t2 = half_tan2(n, wi + wo, ci + co);
    const vfloat<W> lo = min(ci, co), hi = max(ci, co);
    const vfloat<W> s = ward_gaussian<W>(t2, a2) / lo / hi;
    return select0<W>(mask_and(ci > zero, co > zero), min(s, vfloat<W>(brdf_lobe_max)));
}

// ---- shading factors ------------------------------------------------------------------------

/// c_s per lane (textures); the overload below uses m.c_s.
template <int W>
inline Vec3<W> specular_factor(const Material& m, BrdfScaling s, const Vec3<W>& c_s,
                               const Vec3<W>& n, const Vec3<W>& wi, const Vec3<W>& wo) {
    using namespace brdf_detail;
    if (m.k_s == 0.0f) return Vec3<W>{};  // no specular term: the product below would be +0
    const vfloat<W> ci = dot(n, wi), zero(0.0f);
    vfloat<W> lobe = zero;
    switch (m.model) {
        case SpecularModel::phong:
            lobe = phong_lobe(mirror_direction(n, wo), wi, m.exponent);
            return m.k_s * c_s * select0<W>(ci > zero, lobe);
        case SpecularModel::glossy_phong:
            return Vec3<W>{};
        case SpecularModel::blinn_phong:
            lobe = blinn_phong_lobe(n, wi, wo, m.exponent);
            break;
        case SpecularModel::ward:
            lobe = ward_lobe(n, wi, wo, m.alpha);
            break;
        case SpecularModel::ward_duer:
            lobe = ward_duer_lobe(n, wi, wo, m.alpha);
            break;
    }
    const vfloat<W> scale = s == BrdfScaling::physical ? lobe * ci : lobe;
    return m.k_s * c_s * select0<W>(ci > zero, scale);
}

template <int W>
inline Vec3<W> specular_factor(const Material& m, BrdfScaling s, const Vec3<W>& n,
                               const Vec3<W>& wi, const Vec3<W>& wo) {
    return specular_factor(m, s, make_vec3<W>(m.c_s.x, m.c_s.y, m.c_s.z), n, wi, wo);
}

template <int W>
inline Vec3<W> diffuse_factor(const Material& m, BrdfScaling s, const Vec3<W>& c_d,
                              const Vec3<W>& n, const Vec3<W>& wi) {
    using namespace brdf_detail;
    const vfloat<W> ci = dot(n, wi), zero(0.0f);
    const bool fitted = m.model == SpecularModel::blinn_phong || m.model == SpecularModel::ward ||
                        m.model == SpecularModel::ward_duer;
    const vfloat<W> w = fitted && s == BrdfScaling::physical ? ci * inv_pi : ci;
    return c_d * (m.k_d * select0<W>(ci > zero, w));
}

/// c_s per lane (textures); the overload below uses m.c_s.
template <int W>
inline Vec3<W> glossy_weight(const Material& m, BrdfScaling s, const Vec3<W>& c_s, const Vec3<W>& n,
                             const Vec3<W>& wi) {
    using namespace brdf_detail;
    const vfloat<W> ci = dot(n, wi), zero(0.0f);
    const float e = clamp_exponent(m.exponent);
    const vfloat<W> w = s == BrdfScaling::physical ? (e + 2.0f) / (e + 1.0f) * ci : 1.0f;
    return m.k_s * c_s * select0<W>(ci > zero, w);
}

template <int W>
inline Vec3<W> glossy_weight(const Material& m, BrdfScaling s, const Vec3<W>& n,
                             const Vec3<W>& wi) {
    return glossy_weight(m, s, make_vec3<W>(m.c_s.x, m.c_s.y, m.c_s.z), n, wi);
}

// ---- sampling -------------------------------------------------------------------------------

template <int W>
inline Vec3<W> sample_phong_lobe(const Vec3<W>& axis, float e, const vfloat<W>& u1,
                                 const vfloat<W>& u2) {
    using namespace brdf_detail;
    const vfloat<W> lc = log1p<W>(neg(u2)) / (clamp_exponent(e) + 1.0f);
    const vfloat<W> cos_t = exp<W>(lc);
    const vfloat<W> sin_t = sqrt(neg(expm1<W>(2.0f * lc)));
    return around_axis<W>(axis, cos_t, sin_t, two_pi * u1);
}

template <int W>
inline vfloat<W> pdf_phong_lobe(const Vec3<W>& axis, float e, const Vec3<W>& w) {
    using namespace brdf_detail;
    return ((clamp_exponent(e) + 1.0f) * inv_two_pi) * phong_lobe(axis, w, e);
}

namespace brdf_detail {
template <int W>
inline LobeSamplePacket<W> sample_ward_common(const Vec3<W>& n, const Vec3<W>& wo, float alpha,
                                              const vfloat<W>& u1, const vfloat<W>& u2, bool duer) {
    const vfloat<W> zero(0.0f);
    const vfloat<W> co = dot(n, wo);
    const float a2 = alpha_squared(alpha);
    const vfloat<W> t2 = min(neg(a2 * log1p<W>(neg(u2))), vfloat<W>(brdf_tan2_max));
    const vfloat<W> cos_h = vfloat<W>(1.0f) / sqrt(1.0f + t2);
    const vfloat<W> sin_h = sqrt(t2) * cos_h;
    const Vec3<W> h = around_axis<W>(n, cos_h, sin_h, two_pi * u1);
    const vfloat<W> oh = dot(wo, h);
    LobeSamplePacket<W> s;
    s.wi = h * (2.0f * oh) - wo;
    const vfloat<W> ci = dot(n, s.wi);
    const vfloat<W> c3 = cos_h * cos_h * cos_h;
    const vfloat<W> pdf = min(ward_gaussian<W>(t2, a2) / (abs(oh) * c3), vfloat<W>(brdf_lobe_max));
    s.pdf = select0<W>(co > zero, pdf);
    const vfloat<W> w = duer ? oh * c3 / co : oh * c3 * sqrt(ci) / sqrt(co);
    s.weight = select0<W>(mask_and(mask_and(ci > zero, co > zero), oh > zero), w);
    return s;
}
}  // namespace brdf_detail

template <int W>
inline LobeSamplePacket<W> sample_ward(const Vec3<W>& n, const Vec3<W>& wo, float alpha,
                                       const vfloat<W>& u1, const vfloat<W>& u2) {
    return brdf_detail::sample_ward_common<W>(n, wo, alpha, u1, u2, false);
}

template <int W>
inline LobeSamplePacket<W> sample_ward_duer(const Vec3<W>& n, const Vec3<W>& wo, float alpha,
                                            const vfloat<W>& u1, const vfloat<W>& u2) {
    return brdf_detail::sample_ward_common<W>(n, wo, alpha, u1, u2, true);
}

template <int W>
inline vfloat<W> pdf_ward(const Vec3<W>& n, const Vec3<W>& wi, const Vec3<W>& wo, float alpha) {
    using namespace brdf_detail;
    const vfloat<W> ci = dot(n, wi), co = dot(n, wo), zero(0.0f);
    const vfloat<W> hz = abs(ci + co);
    const float a2 = alpha_squared(alpha);
    const vfloat<W> t2 = half_tan2(n, wi + wo, hz);
    const vfloat<W> p = ward_gaussian<W>(t2, a2) * (2.0f * (1.0f + t2)) / hz;
    return select0<W>(mask_and(co > zero, hz > zero), min(p, vfloat<W>(brdf_lobe_max)));
}

template <int W>
inline LobeSamplePacket<W> sample_blinn_phong(const Vec3<W>& n, const Vec3<W>& wo, float exponent,
                                              const vfloat<W>& u1, const vfloat<W>& u2) {
    using namespace brdf_detail;
    const vfloat<W> zero(0.0f);
    const vfloat<W> co = dot(n, wo);
    const float e = clamp_exponent(exponent);
    const vfloat<W> lc = log1p<W>(neg(u2)) / (e + 1.0f);
    const vfloat<W> cos_h = exp<W>(lc);
    const vfloat<W> sin_h = sqrt(neg(expm1<W>(2.0f * lc)));
    const Vec3<W> h = around_axis<W>(n, cos_h, sin_h, two_pi * u1);
    const vfloat<W> oh = dot(wo, h);
    LobeSamplePacket<W> s;
    s.wi = h * (2.0f * oh) - wo;
    const vfloat<W> ci = dot(n, s.wi);
    const vfloat<W> pdf_h = ((e + 1.0f) * inv_two_pi) * exp<W>(e * lc);
    const vfloat<W> pdf = min(pdf_h / (4.0f * abs(oh)), vfloat<W>(brdf_lobe_max));
    s.pdf = select0<W>(co > zero, pdf);
    const vfloat<W> w = (e + 2.0f) / (e + 1.0f) * (4.0f * oh) * ci;
    s.weight = select0<W>(mask_and(mask_and(ci > zero, co > zero), oh > zero), w);
    return s;
}

template <int W>
inline vfloat<W> pdf_blinn_phong(const Vec3<W>& n, const Vec3<W>& wi, const Vec3<W>& wo,
                                 float exponent) {
    using namespace brdf_detail;
    const vfloat<W> ci = dot(n, wi), co = dot(n, wo), zero(0.0f);
    const vfloat<W> hz = abs(ci + co);
    const float e = clamp_exponent(exponent);
    const Vec3<W> h = wi + wo;
    const vfloat<W> t2 = half_tan2(n, h, hz);
    const vfloat<W> pdf_h = ((e + 1.0f) * inv_two_pi) * exp<W>((-0.5f * e) * log1p<W>(t2));
    const vfloat<W> p = min(pdf_h / (2.0f * sqrt(dot(h, h))), vfloat<W>(brdf_lobe_max));
    return select0<W>(mask_and(co > zero, hz > zero), p);
}

}  // namespace raylane::RAYLANE_ISA_NS
