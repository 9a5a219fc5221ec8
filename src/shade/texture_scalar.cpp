// shade: texture lookup, environment mapping and normal maps, the scalar reference
// (texture_scalar.h). texture_packet.h repeats every operation below in the same order.
#include "shade/texture_scalar.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace raylane {

namespace {

using namespace texture_detail;

/// Wrapped (repeat: c - floor(c) outside [0, 1], so that 1 stays 1) and clamped into [0, 1];
/// inf - floor(inf) = NaN becomes 0.
float wrap_coordinate(float c, bool repeat) {
    if (repeat) c = c >= 0.0f && c <= 1.0f ? c : c - std::floor(c);
    c = c >= 0.0f ? c : 0.0f;
    return c > 1.0f ? 1.0f : c;
}

/// Texel (column x, row y from the top); both in range.
vec3 fetch(const Texture& t, int32_t x, int32_t y) {
    const size_t i =
        (static_cast<size_t>(y) * static_cast<size_t>(t.width) + static_cast<size_t>(x)) * 3;
    return vec3(t.texels[i], t.texels[i + 1], t.texels[i + 2]);
}

vec3 image_lookup(const Texture& t, float u, float v, bool repeat_u, bool repeat_v) {
    u = wrap_coordinate(u, repeat_u);
    v = wrap_coordinate(v, repeat_v);
    const float width = static_cast<float>(t.width);
    const float height = static_cast<float>(t.height);
    if (t.filter == TextureFilter::nearest) {
        // in [0, W - 1] and [0, H - 1] since u, v are in [0, 1]
        const auto x = static_cast<int32_t>(std::round(u * (width - 1.0f)));
        const auto y = static_cast<int32_t>(std::round((1.0f - v) * (height - 1.0f)));
        return fetch(t, x, y);
    }
    // bilinear: x in [-1/2, W - 1/2], so x0 in [-1, W - 1] and x1 = x0 + 1 in [0, W]
    const float x = u * width - 0.5f;
    const float y = (1.0f - v) * height - 0.5f;
    const float x_floor = std::floor(x);
    const float y_floor = std::floor(y);
    const float fx = x - x_floor;
    const float fy = y - y_floor;
    int32_t x0 = static_cast<int32_t>(x_floor), x1 = x0 + 1;
    int32_t y0 = static_cast<int32_t>(y_floor), y1 = y0 + 1;
    if (repeat_u) {
        x0 = x0 < 0 ? t.width - 1 : x0;
        x1 = x1 > t.width - 1 ? 0 : x1;
    } else {
        x0 = x0 < 0 ? 0 : x0;
        x1 = x1 > t.width - 1 ? t.width - 1 : x1;
    }
    if (repeat_v) {
        y0 = y0 < 0 ? t.height - 1 : y0;
        y1 = y1 > t.height - 1 ? 0 : y1;
    } else {
        y0 = y0 < 0 ? 0 : y0;
        y1 = y1 > t.height - 1 ? t.height - 1 : y1;
    }
    const vec3 c00 = fetch(t, x0, y0), c10 = fetch(t, x1, y0);
    const vec3 c01 = fetch(t, x0, y1), c11 = fetch(t, x1, y1);
    const float gx = 1.0f - fx, gy = 1.0f - fy;
    vec3 c;
    for (int k = 0; k < 3; ++k)
        c[k] = (c00[k] * gx + c10[k] * fx) * gy + (c01[k] * gx + c11[k] * fx) * fy;
    return c;
}

vec3 checker_lookup(const Texture& t, float u, float v) {
    const float s = std::floor(u * t.checks) + std::floor(v * t.checks);
    const bool even = s - std::floor(s * 0.5f) * 2.0f == 0.0f;  // NaN and inf: odd
    return even ? t.color_a : t.color_b;
}

float dot3(vec3 a, vec3 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }

vec3 normalized(vec3 a) { return a * (1.0f / std::sqrt(dot3(a, a))); }

/// First vector of Duff et al.'s orthonormal basis around unit n (JCGT 2017, listing 3).
vec3 perpendicular(vec3 n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
}

}  // namespace

vec3 texture_lookup(const Texture& t, vec2 uv, bool repeat_u, bool repeat_v) {
    if (std::isnan(uv.x) || std::isnan(uv.y)) return vec3(0.0f);
    if (t.kind == TextureKind::checker) return checker_lookup(t, uv.x, uv.y);
    if (t.width <= 0 || t.height <= 0 ||
        t.texels.size() < static_cast<size_t>(t.width) * static_cast<size_t>(t.height) * 3)
        return vec3(0.0f);
    return image_lookup(t, uv.x, uv.y, repeat_u, repeat_v);
}

vec3 texture_lookup(const Texture& t, vec2 uv) { return texture_lookup(t, uv, t.repeat, t.repeat); }

vec2 latlong_uv(vec3 dir) {
    // |d| of d scaled by its largest component, so that |d|^2 neither overflows nor underflows
    const float ax = std::fabs(dir.x), ay = std::fabs(dir.y), az = std::fabs(dir.z);
    const float axy = ax > ay ? ax : ay;
    const float largest = axy > az ? axy : az;
    const vec3 d(dir.x / largest, dir.y / largest, dir.z / largest);
    float s = d.y / std::sqrt(dot3(d, d));
    s = s > 1.0f ? 1.0f : s;
    s = s < -1.0f ? -1.0f : s;
    // at the poles atan2(0, 0) is implementation-defined (xsimd: NaN): use atan2(d_z, 1) there
    const float x = dir.x == 0.0f && dir.z == 0.0f ? 1.0f : dir.x;
    float u = (std::atan2(dir.z, x) + pi) / two_pi;
    float v = std::asin(s) / pi + 0.5f;
    // within [0, 1] already with std:: (pi / 2 and pi round alike); kept there for any libm
    u = u > 1.0f ? 1.0f : u;
    u = u < 0.0f ? 0.0f : u;
    v = v > 1.0f ? 1.0f : v;
    v = v < 0.0f ? 0.0f : v;
    u = std::isnan(v) ? v : u;  // no direction: both NaN
    return vec2(u, v);
}

vec3 environment_lookup(const Texture& t, vec3 dir) {
    return texture_lookup(t, latlong_uv(dir), true, false);
}

vec3 normal_from_map(NormalMapMode mode, vec3 texel, vec3 n, vec3 dpdu,
                     const glm::mat3& normal_to_world) {
    const vec3 nn = normalized(n);
    vec3 m;
    if (mode == NormalMapMode::replace) {
        const vec3 c = texel - vec3(0.5f);
        const glm::mat3& a = normal_to_world;
        m = vec3(a[0][0] * c.x + a[1][0] * c.y + a[2][0] * c.z,
                 a[0][1] * c.x + a[1][1] * c.y + a[2][1] * c.z,
                 a[0][2] * c.x + a[1][2] * c.y + a[2][2] * c.z);
    } else {
        vec3 t = dpdu - nn * dot3(nn, dpdu);
        const float t2 = dot3(t, t);
        t = t2 > tangent_parallel_fraction * dot3(dpdu, dpdu) ? t * (1.0f / std::sqrt(t2))
                                                              : perpendicular(nn);
        const vec3 b = glm::cross(nn, t);
        const vec3 d = texel * 2.0f - vec3(1.0f);
        m = (t * d.x + b * d.y) + nn * d.z;
    }
    const float m2 = dot3(m, m);
    return m2 >= min_normal_length2 ? m * (1.0f / std::sqrt(m2)) : nn;
}

vec3 keep_above(vec3 ns, vec3 r) {
    const float c = dot3(ns, r);
    if (c >= keep_above_cos) return ns;
    const vec3 t = ns - r * c;
    const float t_length = std::sqrt(dot3(t, t));
    if (!(t_length > 1e-6f)) return r;
    const float s = std::sqrt(1.0f - keep_above_cos * keep_above_cos);
    return t * (s / t_length) + r * keep_above_cos;
}

vec3 face_viewer(vec3 ns, vec3 ng, vec3 wo) {
    const float a = dot3(ns, wo);
    if (a >= keep_above_cos) return ns;
    const float b = dot3(ng, wo);
    const float lambda = b > keep_above_cos ? (keep_above_cos - a) / (b - a) : 1.0f;
    const vec3 m = ns + (ng - ns) * lambda;
    return m / std::sqrt(dot3(m, m));
}

}  // namespace raylane
