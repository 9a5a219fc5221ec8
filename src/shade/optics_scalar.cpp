// shade: Fresnel reflectance, refraction and Beer's law (reference path). Mirrored by
// optics_packet.h; every expression there has the same operation order.
#include "shade/optics_scalar.h"

#include <cmath>

#include "core/min_max.h"

namespace raylane {

namespace {

/// cos^2(theta_t) = 1 - (1 - ci^2) / eta^2, written ((eta - 1)(eta + 1) + ci^2) / eta^2: no
/// cancellation at grazing incidence for eta near 1 (eta - 1 is exact there).
float transmitted_cos2(float ci, float eta) {
    return ((eta - 1.0f) * (eta + 1.0f) + ci * ci) / (eta * eta);
}

}  // namespace

float schlick(float r0, float cos_theta) {
    const float c = min_of(max_of(cos_theta, 0.0f), 1.0f);
    const float m = 1.0f - c;
    const float m2 = m * m;
    return r0 + (1.0f - r0) * (m2 * m2 * m);
}

float fresnel_dielectric(float cos_i, float eta, float cos_t) {
    const float ci = min_of(max_of(cos_i, 0.0f), 1.0f);
    const float ct = min_of(max_of(cos_t, 0.0f), 1.0f);
    const float r_par = (eta * ci - ct) / (eta * ci + ct);
    const float r_perp = (ci - eta * ct) / (ci + eta * ct);
    const float r = 0.5f * (r_par * r_par + r_perp * r_perp);
    return ci > 0.0f ? r : 1.0f;
}

float fresnel_dielectric(float cos_i, float eta) {
    const float ci = min_of(max_of(cos_i, 0.0f), 1.0f);
    const float cos2_t = transmitted_cos2(ci, eta);
    const float cos_t = eta == 1.0f ? ci : std::sqrt(max_of(cos2_t, 0.0f));
    // index-matched (eta 1): no interface, R = 0 even where 1 - cos^2 rounds to 1
    return cos2_t > 0.0f || eta == 1.0f ? fresnel_dielectric(ci, eta, cos_t) : 1.0f;
}

vec3 reflect_direction(vec3 d, vec3 n) { return d - n * (2.0f * glm::dot(d, n)); }

bool refract_direction(vec3 d, vec3 n_facing, float eta, vec3& t, float& cos_t) {
    const float ci = min_of(max_of(-glm::dot(d, n_facing), 0.0f), 1.0f);
    if (eta == 1.0f) {
        t = d;
        cos_t = ci;
        return true;
    }
    const float cos2_t = transmitted_cos2(ci, eta);
    if (!(cos2_t > 0.0f)) {
        t = reflect_direction(d, n_facing);
        cos_t = 0.0f;
        return false;
    }
    cos_t = std::sqrt(cos2_t);
    t = d / eta - n_facing * (cos_t - ci / eta);
    return true;
}

namespace {

float beer_channel(float filter, float distance) {
    if (!(distance > 0.0f) || !(filter < 1.0f)) return 1.0f;
    if (!(filter > 0.0f)) return 0.0f;
    return std::exp(distance * std::log(filter));  // distance = inf: exp(-inf) = 0
}
}  // namespace

vec3 beer_transmittance(vec3 filter, float distance) {
    return vec3(beer_channel(filter.x, distance), beer_channel(filter.y, distance),
                beer_channel(filter.z, distance));
}

}  // namespace raylane
