// Test support: the awkward floats the numerics tests feed in, and small checks of the results.
// Tests take them in with `using namespace test;`; the names must not be those of locals in the
// library's inline code (nan, inf), which Clang's -Wshadow would report.
#pragma once

#include <cmath>
#include <limits>

#include "core/ray_packet.h"
#include "simd/lanes.h"

namespace raylane::test {

inline const float nan_f = std::numeric_limits<float>::quiet_NaN();
inline const float inf_f = std::numeric_limits<float>::infinity();
inline const float flt_max = std::numeric_limits<float>::max();
inline constexpr double pi_d = 3.14159265358979323846;

/// Uniform numbers at and next to the ends of [0, 1], for samplers.
inline const float extreme_u[] = {0.0f, 0x1.0p-32f, 0x1.0p-24f, 0.5f, 1.0f - 0x1.0p-24f, 1.0f};

inline bool finite3(vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Lane k of a packet of vectors.
template <int W>
vec3 lane3(const Vec3<W>& v, int k) {
    return vec3(get(v.x, k), get(v.y, k), get(v.z, k));
}

}  // namespace raylane::test
