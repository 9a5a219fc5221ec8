// shade: Fresnel reflectance, mirror and refracted directions, and Beer's law (the reference
// path). Mirrored by optics_packet.h: same names, same order, same operation order.
#pragma once

#include "core/ray.h"

namespace raylane {

// eta is the report's relative index n_transmitted / n_incident: eta = n when entering glass of
// index n from air, 1 / n when leaving (report-scenes.md 1.5).

/// Schlick 1994: r0 + (1 - r0)(1 - cos)^5, cos clamped to [0, 1] (NaN -> 0). r0 > 1 is allowed
/// (the report's fractal), giving R > 1.
float schlick(float r0, float cos_theta);

/// Exact unpolarised dielectric reflectance for cos_i, cos_t >= 0 (both clamped to [0, 1]):
/// r_par = (eta ci - ct) / (eta ci + ct), r_perp = (ci - eta ct) / (ci + eta ct),
/// R = (r_par^2 + r_perp^2) / 2; T = 1 - R. R = 1 when ci = 0 (grazing; also the 0/0 at the
/// total-internal-reflection boundary).
float fresnel_dielectric(float cos_i, float eta, float cos_t);
/// The same with cos_t from Snell's law as in refract_direction; 1 under total internal
/// reflection; exactly 0 for eta == 1.
float fresnel_dielectric(float cos_i, float eta);

/// d - 2 (d.n) n.
vec3 reflect_direction(vec3 d, vec3 n);

/// Refracts unit d at unit n_facing (dot(d, n_facing) <= 0): cos_i = -d.n (clamped to [0, 1]),
/// cos^2_t = 1 - (1 - cos^2_i) / eta^2 (evaluated as ((eta - 1)(eta + 1) + cos^2_i) / eta^2, which
/// does not cancel at grazing incidence), t = d / eta - n_facing (cos_t - cos_i / eta). eta == 1
/// gives t = d and cos_t = cos_i exactly. Returns false on total internal reflection
/// (cos^2_t <= 0, i.e. sin^2_t >= 1), and then sets t to the mirror direction and cos_t to 0.
bool refract_direction(vec3 d, vec3 n_facing, float eta, vec3& t, float& cos_t);

/// Beer's law: filter^distance per channel, as exp(distance log(filter)) with explicit rules:
/// distance <= 0 (or NaN) -> 1; filter >= 1 (or NaN) -> 1, also for infinite distance;
/// filter <= 0 -> 0.
/// Infinite distance with filter < 1 gives 0. Never NaN.
vec3 beer_transmittance(vec3 filter, float distance);

}  // namespace raylane
