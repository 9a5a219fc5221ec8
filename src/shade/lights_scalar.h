// shade: where a shading point sees each light - direction, distance and factor of one light
// sample (point, directional, and stratified samples of rectangle, disc and box area lights).
// The reference path; mirrored by lights_packet.h.
#pragma once

#include <cmath>
#include <numbers>

#include "core/ray.h"
#include "scene/scene.h"

namespace raylane {

/// The light as seen from a point: unit direction towards it, distance (infinity for
/// directional lights) and the factor F of report-scenes.md 1.4 (intensity / d^2 or intensity).
struct LightSample {
    vec3 dir{0.0f, 1.0f, 0.0f};
    float distance = infinity;
    float factor = 0.0f;
    bool valid = false;  ///< false when the point sits on the light (d = 0)
};

/// Stratified position in the unit square of sample i of n: the cell (i mod m, i div m) of an
/// m x m grid, m = floor(sqrt(n)), jittered by (u1, u2); samples past m^2 are uniform.
inline vec2 stratified_square(int i, int n, float u1, float u2) {
    const int m = static_cast<int>(std::sqrt(static_cast<float>(n)));
    if (i >= m * m) return vec2(u1, u2);
    const float inv = 1.0f / static_cast<float>(m);
    return vec2((static_cast<float>(i % m) + u1) * inv, (static_cast<float>(i / m) + u2) * inv);
}

/// Concentric map of the unit square to the unit disc (Shirley, Chiu, "A Low Distortion Map
/// Between Disk and Square", JGT 1997): uniform in, uniform out, strata kept compact.
inline vec2 concentric_disk(vec2 s) {
    const float a = 2.0f * s.x - 1.0f, b = 2.0f * s.y - 1.0f;
    if (a == 0.0f && b == 0.0f) return vec2(0.0f);
    constexpr float quarter_pi = 0.25f * std::numbers::pi_v<float>;
    float r, phi;
    if (std::fabs(a) > std::fabs(b)) {
        r = a;
        phi = quarter_pi * (b / a);
    } else {
        r = b;
        phi = 2.0f * quarter_pi - quarter_pi * (a / b);
    }
    return vec2(r * std::cos(phi), r * std::sin(phi));
}

/// A point on (or in) an area light for the unit-square position s and third coordinate u3.
inline vec3 area_light_point(const Light& light, vec2 s, float u3) {
    switch (light.kind) {
        case LightKind::rect:
            return light.position + s.x * light.edge_u + s.y * light.edge_v;
        case LightKind::disk: {
            const vec3 n = light.direction;
            const vec3 a = std::fabs(n.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 0.0f, 1.0f);
            const vec3 t = glm::normalize(glm::cross(n, a));
            const vec3 b = glm::cross(n, t);
            const vec2 d = concentric_disk(s);
            return light.position + light.radius * (d.x * t + d.y * b);
        }
        case LightKind::box:
            return light.position + vec3(s.x, s.y, u3) * light.edge_u;
        default:
            return light.position;
    }
}

/// Sample i of n of `light` from `origin`; u1, u2, u3 uniform in [0, 1) (ignored by point and
/// directional lights).
inline LightSample sample_light(const Light& light, vec3 origin, int i, int n, float u1, float u2,
                                float u3) {
    LightSample ls;
    if (light.kind == LightKind::directional) {
        ls.dir = light.direction;
        ls.factor = light.intensity;
        ls.valid = true;
        return ls;
    }
    const vec3 p = light.kind == LightKind::point
                       ? light.position
                       : area_light_point(light, stratified_square(i, n, u1, u2), u3);
    const vec3 to = p - origin;
    const float d2 = glm::dot(to, to);
    if (!(d2 > 0.0f)) return ls;
    const float d = std::sqrt(d2);
    ls.dir = to / d;
    ls.distance = d;
    ls.factor = light.intensity / d2;
    ls.valid = true;
    return ls;
}

}  // namespace raylane
