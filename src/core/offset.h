// core: spawning secondary rays without self-intersection, at any scene scale.
// Waechter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
// Ray Tracing Gems ch. 6 (2019). Integer arithmetic on the float bits; the packet twin must
// produce the same bits from the same inputs.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "core/ray.h"

namespace raylane {

inline constexpr float offset_origin = 1.0f / 32.0f;
inline constexpr float offset_float_scale = 1.0f / 65536.0f;
inline constexpr float offset_int_scale = 256.0f;

/// Moves p off the surface along n (n points to the side the new ray leaves from): 256 ulps
/// times the normal component per coordinate, or 2^-16 times it near the origin.
inline vec3 offset_ray_origin(vec3 p, vec3 n) {
    vec3 out;
    for (int k = 0; k < 3; ++k) {
        const int32_t of_i = static_cast<int32_t>(offset_int_scale * n[k]);
        const int32_t bits = std::bit_cast<int32_t>(p[k]);
        const float p_i = std::bit_cast<float>(bits + (p[k] < 0.0f ? -of_i : of_i));
        out[k] = std::fabs(p[k]) < offset_origin ? p[k] + offset_float_scale * n[k] : p_i;
    }
    return out;
}

}  // namespace raylane
