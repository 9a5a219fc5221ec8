// core: spawning secondary rays without self-intersection, at any scene scale.
// Waechter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
// Ray Tracing Gems ch. 6 (2019), with their two constants for the region near zero taken
// relative to the ray's reach instead of to a unit-sized scene. Integer arithmetic on the float
// bits; the packet twin (offset_packet.h) produces the same bits from the same inputs.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "core/ray.h"

namespace raylane {

inline constexpr float offset_origin = 1.0f / 32.0f;
inline constexpr float offset_float_scale = 1.0f / 65536.0f;
inline constexpr float offset_int_scale = 256.0f;

/// The scale of the rounding error of a hit point o + t d: |o| + t |d| in the max norm.
inline float ray_reach(const Ray& ray, float t) {
    auto max_abs = [](vec3 v) {
        const vec3 a = glm::abs(v);
        const float xy = a.x > a.y ? a.x : a.y;  // the order of simd max: max(max(x, y), z)
        return xy > a.z ? xy : a.z;
    };
    return max_abs(ray.org) + t * max_abs(ray.dir);
}

/// Moves p off the surface along n (n points to the side the new ray leaves from): 256 ulps of
/// each coordinate times the normal component, or, for coordinates within reach / 32 of zero
/// (where ulps are smaller than the hit point's error), reach / 65536 times it. `reach` is
/// ray_reach of the ray that found p (numerics.md section 3).
inline vec3 offset_ray_origin(vec3 p, vec3 n, float reach) {
    const float near_zero = offset_origin * reach, step = offset_float_scale * reach;
    vec3 out;
    for (int k = 0; k < 3; ++k) {
        const float scaled = offset_int_scale * n[k];
        const int32_t of_i = scaled == scaled ? static_cast<int32_t>(scaled) : 0;  // NaN: 0
        const int32_t bits = std::bit_cast<int32_t>(p[k]);
        const float p_i = std::bit_cast<float>(bits + (p[k] < 0.0f ? -of_i : of_i));
        out[k] = std::fabs(p[k]) < near_zero ? p[k] + step * n[k] : p_i;
    }
    return out;
}

}  // namespace raylane
