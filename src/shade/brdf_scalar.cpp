// shade: BRDF lobes, shading factors and lobe sampling (reference path).
// Mirrored by brdf_packet.h; every expression there has the same operation order.
#include "shade/brdf_scalar.h"

#include <cmath>

#include "core/min_max.h"

namespace raylane {

namespace {

constexpr float pi = std::numbers::pi_v<float>;
constexpr float inv_pi = std::numbers::inv_pi_v<float>;
constexpr float two_pi = 2.0f * pi;
constexpr float four_pi = 4.0f * pi;
constexpr float inv_two_pi = 0.5f * inv_pi;

/// Exponent e >= 0 (NaN -> 0).
float clamp_exponent(float e) { return max_of(e, 0.0f); }

/// alpha^2 with alpha >= brdf_alpha_min (NaN -> the minimum).
float alpha_squared(float alpha) {
    const float a = max_of(alpha, brdf_alpha_min);
    return a * a;
}

/// tan^2 of the angle between unit n and H = wi + wo, as |n x H|^2 / hz^2 with hz = n.H,
/// capped at brdf_tan2_max (hz = 0 or 0/0 give the cap).
float half_tan2(vec3 n, vec3 h, float hz) {
    const vec3 c = glm::cross(n, h);
    return min_of(glm::dot(c, c) / (hz * hz), brdf_tan2_max);
}

/// exp(-tan^2 / alpha^2) / (4 pi alpha^2): the Ward Gaussian and its constant, at most 8e6.
float ward_gaussian(float t2, float a2) { return std::exp(-(t2 / a2)) / (four_pi * a2); }

/// A direction with polar cosine / sine (cos_t, sin_t) and azimuth phi around unit axis.
vec3 around_axis(vec3 axis, float cos_t, float sin_t, float phi) {
    vec3 t, b;
    orthonormal_basis(axis, t, b);
    return t * (sin_t * std::cos(phi)) + b * (sin_t * std::sin(phi)) + axis * cos_t;
}

LobeSample sample_ward_common(vec3 n, vec3 wo, float alpha, float u1, float u2, bool duer) {
    const float co = glm::dot(n, wo);
    const float a2 = alpha_squared(alpha);
    // tan^2(theta_h) = alpha^2 Exp(1); 1 - u2 in (0, 1]
    const float t2 = min_of(-(a2 * std::log1p(-u2)), brdf_tan2_max);
    const float cos_h = 1.0f / std::sqrt(1.0f + t2);
    const float sin_h = std::sqrt(t2) * cos_h;
    const vec3 h = around_axis(n, cos_h, sin_h, two_pi * u1);
    const float oh = glm::dot(wo, h);
    LobeSample s;
    s.wi = h * (2.0f * oh) - wo;
    const float ci = glm::dot(n, s.wi);
    const float c3 = cos_h * cos_h * cos_h;
    const float pdf = min_of(ward_gaussian(t2, a2) / (std::fabs(oh) * c3), brdf_lobe_max);
    s.pdf = co > 0.0f ? pdf : 0.0f;
    const float w = duer ? oh * c3 / co : oh * c3 * std::sqrt(ci) / std::sqrt(co);
    s.weight = ci > 0.0f && co > 0.0f && oh > 0.0f ? w : 0.0f;
    return s;
}

}  // namespace

// ---- frames ---------------------------------------------------------------------------------

void orthonormal_basis(vec3 n, vec3& t, vec3& b) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    t = vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = vec3(c, sign + n.y * n.y * a, -n.y);
}

vec3 mirror_direction(vec3 n, vec3 wo) { return n * (2.0f * glm::dot(n, wo)) - wo; }

// ---- lobes ----------------------------------------------------------------------------------

float phong_lobe(vec3 axis, vec3 w, float e) {
    const vec3 d = w - axis;
    const float chord2 = glm::dot(d, d);  // 2 (1 - cos) for unit vectors
    if (!(chord2 < 2.0f)) return 0.0f;
    return std::exp(clamp_exponent(e) * std::log1p(-0.5f * chord2));
}

float blinn_phong_lobe(vec3 n, vec3 wi, vec3 wo, float exponent) {
    const float ci = glm::dot(n, wi), co = glm::dot(n, wo);
    if (!(ci > 0.0f && co > 0.0f)) return 0.0f;
    const float e = clamp_exponent(exponent);
    const float t2 = half_tan2(n, wi + wo, ci + co);
    return ((e + 2.0f) * inv_two_pi) * std::exp((-0.5f * e) * std::log1p(t2));
}

float ward_lobe(vec3 n, vec3 wi, vec3 wo, float alpha) {
    const float ci = glm::dot(n, wi), co = glm::dot(n, wo);
    if (!(ci > 0.0f && co > 0.0f)) return 0.0f;
    const float a2 = alpha_squared(alpha);
    const float t2 = half_tan2(n, wi + wo, ci + co);
    // divide by the smaller cosine first: symmetric in (ci, co), no underflow of ci co
    const float lo = min_of(ci, co), hi = max_of(ci, co);
    return min_of(ward_gaussian(t2, a2) / std::sqrt(lo) / std::sqrt(hi), brdf_lobe_max);
}

float ward_duer_lobe(vec3 n, vec3 wi, vec3 wo, float alpha) {
    const float ci = glm::dot(n, wi), co = glm::dot(n, wo);
    if (!(ci > 0.0f && co > 0.0f)) return 0.0f;
    const float a2 = alpha_squared(alpha);
    const float t2 = half_tan2(n, wi + wo, ci + co);
    const float lo = min_of(ci, co), hi = max_of(ci, co);
    return min_of(ward_gaussian(t2, a2) / lo / hi, brdf_lobe_max);
}

// ---- shading factors ------------------------------------------------------------------------

vec3 specular_factor(const Material& m, BrdfScaling s, vec3 n, vec3 wi, vec3 wo) {
    return specular_factor(m, s, m.c_s, n, wi, wo);
}

vec3 specular_factor(const Material& m, BrdfScaling s, vec3 c_s, vec3 n, vec3 wi, vec3 wo) {
    if (m.k_s == 0.0f) return vec3(0.0f);  // no specular term: the product below would be +0
    const float ci = glm::dot(n, wi);
    float lobe = 0.0f;
    switch (m.model) {
        case SpecularModel::phong:
            lobe = phong_lobe(mirror_direction(n, wo), wi, m.exponent);
            return m.k_s * c_s * (ci > 0.0f ? lobe : 0.0f);
        case SpecularModel::glossy_phong:
            return vec3(0.0f);
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
    const float scale = s == BrdfScaling::physical ? lobe * ci : lobe;
    return m.k_s * c_s * (ci > 0.0f ? scale : 0.0f);
}

vec3 diffuse_factor(const Material& m, BrdfScaling s, vec3 c_d, vec3 n, vec3 wi) {
    const float ci = glm::dot(n, wi);
    const bool fitted = m.model == SpecularModel::blinn_phong || m.model == SpecularModel::ward ||
                        m.model == SpecularModel::ward_duer;
    const float w = fitted && s == BrdfScaling::physical ? ci * inv_pi : ci;
    return c_d * (m.k_d * (ci > 0.0f ? w : 0.0f));
}

vec3 glossy_weight(const Material& m, BrdfScaling s, vec3 n, vec3 wi) {
    return glossy_weight(m, s, m.c_s, n, wi);
}

vec3 glossy_weight(const Material& m, BrdfScaling s, vec3 c_s, vec3 n, vec3 wi) {
    const float ci = glm::dot(n, wi);
    const float e = clamp_exponent(m.exponent);
    const float w = s == BrdfScaling::physical ? (e + 2.0f) / (e + 1.0f) * ci : 1.0f;
    return m.k_s * c_s * (ci > 0.0f ? w : 0.0f);
}

// ---- sampling -------------------------------------------------------------------------------

vec3 sample_phong_lobe(vec3 axis, float e, float u1, float u2) {
    const float lc = std::log1p(-u2) / (clamp_exponent(e) + 1.0f);  // ln cos, <= 0
    const float cos_t = std::exp(lc);
    const float sin_t = std::sqrt(-std::expm1(2.0f * lc));
    return around_axis(axis, cos_t, sin_t, two_pi * u1);
}

float pdf_phong_lobe(vec3 axis, float e, vec3 w) {
    return ((clamp_exponent(e) + 1.0f) * inv_two_pi) * phong_lobe(axis, w, e);
}

LobeSample sample_ward(vec3 n, vec3 wo, float alpha, float u1, float u2) {
    return sample_ward_common(n, wo, alpha, u1, u2, false);
}

LobeSample sample_ward_duer(vec3 n, vec3 wo, float alpha, float u1, float u2) {
    return sample_ward_common(n, wo, alpha, u1, u2, true);
}

float pdf_ward(vec3 n, vec3 wi, vec3 wo, float alpha) {
    const float ci = glm::dot(n, wi), co = glm::dot(n, wo);
    const float hz = std::fabs(ci + co);
    if (!(co > 0.0f && hz > 0.0f)) return 0.0f;
    const float a2 = alpha_squared(alpha);
    const float t2 = half_tan2(n, wi + wo, hz);
    return min_of(ward_gaussian(t2, a2) * (2.0f * (1.0f + t2)) / hz, brdf_lobe_max);
}

LobeSample sample_blinn_phong(vec3 n, vec3 wo, float exponent, float u1, float u2) {
    const float co = glm::dot(n, wo);
    const float e = clamp_exponent(exponent);
    const float lc = std::log1p(-u2) / (e + 1.0f);  // ln cos(theta_h)
    const float cos_h = std::exp(lc);
    const float sin_h = std::sqrt(-std::expm1(2.0f * lc));
    const vec3 h = around_axis(n, cos_h, sin_h, two_pi * u1);
    const float oh = glm::dot(wo, h);
    LobeSample s;
    s.wi = h * (2.0f * oh) - wo;
    const float ci = glm::dot(n, s.wi);
    const float pdf_h = ((e + 1.0f) * inv_two_pi) * std::exp(e * lc);
    const float pdf = min_of(pdf_h / (4.0f * std::fabs(oh)), brdf_lobe_max);
    s.pdf = co > 0.0f ? pdf : 0.0f;
    const float w = (e + 2.0f) / (e + 1.0f) * (4.0f * oh) * ci;
    s.weight = ci > 0.0f && co > 0.0f && oh > 0.0f ? w : 0.0f;
    return s;
}

float pdf_blinn_phong(vec3 n, vec3 wi, vec3 wo, float exponent) {
    const float ci = glm::dot(n, wi), co = glm::dot(n, wo);
    const float hz = std::fabs(ci + co);
    if (!(co > 0.0f && hz > 0.0f)) return 0.0f;
    const float e = clamp_exponent(exponent);
    const vec3 h = wi + wo;
    const float t2 = half_tan2(n, h, hz);
    const float pdf_h = ((e + 1.0f) * inv_two_pi) * std::exp((-0.5f * e) * std::log1p(t2));
    // wo.h = |H| / 2 for unit wi, wo
    return min_of(pdf_h / (2.0f * std::sqrt(glm::dot(h, h))), brdf_lobe_max);
}

}  // namespace raylane
