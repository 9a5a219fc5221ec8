// shade: where a shading point sees each light - direction, distance and factor of one light
// sample (point, directional, and stratified samples of rectangle, disc and box area lights).
// The reference path; mirrored by lights_packet.h.
#pragma once

#include <cmath>
#include <limits>
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

/// The stratum of sample i of n in the unit square: n cells of equal area 1/n in m = floor(sqrt n)
/// columns, the first n mod m columns holding one cell more than the others. Column widths are
/// proportional to their cell counts, so every n is stratified (not only squares) and a uniform
/// point in each cell gives a uniform, unbiased sample set.
struct Stratum {
    float x0 = 0.0f;     ///< left edge of the column times n: the index of its first cell
    float cells = 1.0f;  ///< cells in the column; the column is cells / n wide
    float row = 0.0f;    ///< the cell's row in its column (of height 1 / cells)
    float n = 1.0f;
};

inline Stratum stratum_of(int i, int n) {
    const int m = static_cast<int>(std::sqrt(static_cast<float>(n)));
    const int q = n / m, r = n % m;  // r columns of q + 1 cells, then m - r of q
    const int tall = r * (q + 1);    // cells in the taller columns
    const int cells = i < tall ? q + 1 : q;
    const int first = i < tall ? i - i % cells : tall + (i - tall) - (i - tall) % cells;
    return {static_cast<float>(first), static_cast<float>(cells), static_cast<float>(i - first),
            static_cast<float>(n)};
}

/// Stratified position in the unit square of sample i of n (stratum_of), jittered by (u1, u2).
inline vec2 stratified_square(int i, int n, float u1, float u2) {
    const Stratum s = stratum_of(i, n);
    return vec2((s.x0 + u1 * s.cells) / s.n, (s.row + u2) / s.cells);
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
    const float factor = light.intensity / d2;
    // on the light (d = 0), or so close that intensity / d^2 overflows: no usable sample
    if (!(d2 > 0.0f) || !(factor < std::numeric_limits<float>::infinity())) return ls;
    const float d = std::sqrt(d2);
    ls.dir = to / d;
    ls.distance = d;
    ls.factor = factor;
    ls.valid = true;
    return ls;
}

}  // namespace raylane
