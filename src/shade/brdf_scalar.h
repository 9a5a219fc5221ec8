// shade: BRDF lobes, shading factors and lobe sampling at one shading point (the reference
// path; Fresnel, refraction and Beer's law are in optics_scalar.h). Mirrored by brdf_packet.h: same
// names, same order, same operation order.
//
// Conventions (brdf-reference.md, report-scenes.md 1.5): all vectors are world-space unit vectors;
// `n` is the shading normal turned to face the viewer, `wo` points towards the viewer (minus the
// ray direction), `wi` towards the light; ci = n.wi, co = n.wo. Everything is float32; narrow
// lobes are evaluated the stable way of brdf-reference.md section 5 (log space, log1p / expm1,
// chord lengths, tan^2 from the un-normalised half vector H = wi + wo, no acos / tan).
// For finite unit vectors, exponents in [0, 1e6] and alpha in [1e-4, 1] no result is NaN or inf.
#pragma once

#include <numbers>

#include "core/ray.h"
#include "scene/scene.h"

namespace raylane {

// ---- constants shared by both paths ---------------------------------------------------------

/// Cap on lobe values and pdfs. Reached only when the true value exceeds float range in practice
/// (Ward-Duer at its peak with ci = co < 3e-13 and alpha = 1e-4), so results stay finite.
inline constexpr float brdf_lobe_max = 1e32f;
/// Cap on tan^2(theta_h) (H nearly tangent; the lobes are 0 there anyway).
inline constexpr float brdf_tan2_max = 1e30f;
/// Smaller Ward alphas are raised to this (keeps 1 / alpha^2 finite; the fits use >= 0.0137).
inline constexpr float brdf_alpha_min = 1e-4f;

/// One direction drawn from a specular lobe.
struct LobeSample {
    vec3 wi{0.0f};        ///< unit direction towards the light; may lie below the surface
    float pdf = 0.0f;     ///< density of wi per unit solid angle (over the whole sphere)
    float weight = 0.0f;  ///< S(wi, wo) ci / pdf per unit rho_s; 0 when ci <= 0 or co <= 0
};

// ---- frames ---------------------------------------------------------------------------------

/// t, b such that (t, b, n) is a right-handed orthonormal frame, for unit n (Duff, Burgess,
/// Christensen, Hery, Kensler, Liani, Villemin 2017, "Building an Orthonormal Basis,
/// Revisited", JCGT 6(1)); no branch on a threshold, continuous except across n.z = 0.
void orthonormal_basis(vec3 n, vec3& t, vec3& b);

/// Mirror direction of wo about n: 2 (n.wo) n - wo.
vec3 mirror_direction(vec3 n, vec3 wo);

// ---- lobes ----------------------------------------------------------------------------------

/// cos^e of the angle between unit `axis` and unit `w`, 0 when the cosine is <= 0. Evaluated as
/// exp(e log1p(-|w - axis|^2 / 2)) (chord length: exact for unit vectors, well conditioned at
/// the peak). e < 0 is treated as 0.
float phong_lobe(vec3 axis, vec3 w, float e);

/// Ngan et al. 2005 Blinn-Phong lobe S = (e + 2) / (2 pi) cos^e(theta_h), theta_h between n and
/// the half vector; cos^e = exp(-e/2 log1p(tan^2 theta_h)). 0 unless ci > 0 and co > 0.
float blinn_phong_lobe(vec3 n, vec3 wi, vec3 wo, float exponent);

/// Isotropic Ward lobe S = exp(-tan^2(theta_h) / alpha^2) / (4 pi alpha^2 sqrt(ci co))
/// (Ward 1992, "Measuring and Modeling Anisotropic Reflection"). 0 unless ci > 0 and co > 0.
float ward_lobe(vec3 n, vec3 wi, vec3 wo, float alpha);

/// Ward lobe with Dür's normalisation, 1 / (4 pi alpha^2 ci co) (Dür 2006, "An Improved
/// Normalization for the Ward Reflectance Model", JGT 11(1)). 0 unless ci > 0 and co > 0.
float ward_duer_lobe(vec3 n, vec3 wi, vec3 wo, float alpha);

// ---- shading factors ------------------------------------------------------------------------

/// The specular term per unit light radiance: what c_light F multiplies.
///   phong: k_s c_s cos^e(alpha), alpha between wi and the mirror of wo (report-scenes.md 1.5:
///     no cos(theta_i), no normalisation; the same in both scalings). Zero when cos(alpha) <= 0:
///     the report's code powers the signed cosine (a faint second lobe for even e); we clamp.
///   glossy_phong: zero (its highlights come only through glossy rays).
///   blinn_phong, ward, ward_duer, with rho_s = k_s c_s: physical = rho_s S(wi, wo) ci,
///     report = rho_s S(wi, wo) (the report's code drops ci).
/// Every model is zero unless ci > 0 (and co > 0 for the fitted lobes).
vec3 specular_factor(const Material& m, BrdfScaling s, vec3 n, vec3 wi, vec3 wo);
/// The same with c_s given (a texture that also replaces the specular colour).
vec3 specular_factor(const Material& m, BrdfScaling s, vec3 c_s, vec3 n, vec3 wi, vec3 wo);

/// The diffuse term per unit light radiance (c_d passed separately: textures replace it).
/// phong and glossy_phong: k_d c_d ci in both scalings (the report has no 1/pi); fitted models:
/// physical k_d c_d ci / pi, report k_d c_d ci. Zero when ci <= 0.
vec3 diffuse_factor(const Material& m, BrdfScaling s, vec3 c_d, vec3 n, vec3 wi);

/// Weight of one glossy sample's traced radiance, before the division by the sample count N
/// (samples below the surface return 0 but still count in N). Uses k_s, c_s and exponent e:
///   report: k_s c_s when ci > 0 (the BRDF-over-pdf ratio of Suffern 2007, chapter 25);
///   physical: k_s c_s (e + 2) / (e + 1) ci, the exact weight of the energy-normalised modified
///     Phong BRDF k_s c_s (e + 2) / (2 pi) cos^e sampled by sample_phong_lobe (Lafortune and
///     Willems 1994, "Using the Modified Phong Reflectance Model for Physically Based Rendering").
vec3 glossy_weight(const Material& m, BrdfScaling s, vec3 n, vec3 wi);
/// The same with c_s given.
vec3 glossy_weight(const Material& m, BrdfScaling s, vec3 c_s, vec3 n, vec3 wi);

// ---- sampling -------------------------------------------------------------------------------
// u1, u2 in [0, 1). Log-space forms: cos = exp(lc), sin = sqrt(-expm1(2 lc)) (section 5.1).

/// Direction around unit `axis` with density (e + 1) / (2 pi) cos^e over the cap around axis:
/// phi = 2 pi u1, cos = (1 - u2)^(1 / (e + 1)) = exp(log1p(-u2) / (e + 1)) (Suffern 2007, 7.2).
vec3 sample_phong_lobe(vec3 axis, float e, float u1, float u2);
/// Density of sample_phong_lobe at unit w: (e + 1) / (2 pi) phong_lobe(axis, w, e).
float pdf_phong_lobe(vec3 axis, float e, vec3 w);

/// Half-vector sampling of the Ward lobe (Walter 2005, "Notes on the Ward BRDF", PCG-05-06):
/// phi_h = 2 pi u1, tan^2(theta_h) = -alpha^2 log1p(-u2), wi = 2 (wo.h) h - wo. Weight
/// (wo.h) cos^3(theta_h) sqrt(ci / co). pdf = 0 and weight = 0 when co <= 0.
LobeSample sample_ward(vec3 n, vec3 wo, float alpha, float u1, float u2);
/// The same distribution, weighted for Ward-Duer: (wo.h) cos^3(theta_h) / co.
LobeSample sample_ward_duer(vec3 n, vec3 wo, float alpha, float u1, float u2);
/// Density of sample_ward (and sample_ward_duer) at wi, over the whole sphere:
/// exp(-tan^2 / alpha^2) / (4 pi alpha^2 (wi.h) cos^3 theta_h) = exp(..) (1 + tan^2) /
/// (2 pi alpha^2 |n.H|). Below-surface wi keep their density (they are drawn, and weigh 0).
/// 0 when co <= 0 or n.H = 0.
float pdf_ward(vec3 n, vec3 wi, vec3 wo, float alpha);

/// Half-vector sampling of the Blinn-Phong lobe: cos(theta_h) = (1 - u2)^(1 / (e + 1)),
/// pdf_h = (e + 1) / (2 pi) cos^e(theta_h), pdf = pdf_h / (4 wo.h); weight
/// (e + 2) / (e + 1) 4 (wo.h) ci (brdf-reference.md 4.4). pdf = weight = 0 when co <= 0.
LobeSample sample_blinn_phong(vec3 n, vec3 wo, float exponent, float u1, float u2);
/// Density of sample_blinn_phong at wi, over the whole sphere; 0 when co <= 0 or n.H = 0.
float pdf_blinn_phong(vec3 n, vec3 wi, vec3 wo, float exponent);

}  // namespace raylane
