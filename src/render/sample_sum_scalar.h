// render: what a pixel does with its samples - classify each (finite, NaN, infinite) by its bits
// and add the finite ones into a compensated sum. The reference path; mirrored by
// sample_sum_packet.h, operation for operation, so both paths give the same bits.
#pragma once

#include <bit>
#include <cstdint>

#include "core/ray.h"

namespace raylane {

/// Exponent bits all ones: infinite or NaN. A bit test, so no compiler flag can remove it
/// (numerics.md §18).
inline bool nonfinite_bits(float v) {
    return (std::bit_cast<uint32_t>(v) & 0x7f800000u) == 0x7f800000u;
}
/// NaN: exponent all ones and a non-zero mantissa.
inline bool nan_bits(float v) { return (std::bit_cast<uint32_t>(v) & 0x7fffffffu) > 0x7f800000u; }

/// What a sample is: a NaN in any channel makes it NaN; otherwise an infinite channel, infinite.
enum class SampleKind : uint8_t { finite, nan, inf };

inline SampleKind sample_kind(vec3 c) {
    if (nan_bits(c.x) || nan_bits(c.y) || nan_bits(c.z)) return SampleKind::nan;
    if (nonfinite_bits(c.x) || nonfinite_bits(c.y) || nonfinite_bits(c.z)) return SampleKind::inf;
    return SampleKind::finite;
}

/// A pixel's finite samples: a Kahan-compensated float sum (Kahan, "Further remarks on reducing
/// truncation errors", CACM 8(1), 1965) and their count. Relative error about 2 ulp whatever
/// the count (a plain float sum stops growing at 2^24 samples of equal value; numerics.md §19).
/// Needs value-safe float maths (no -ffast-math, which deletes the compensation).
struct PixelSum {
    vec3 sum{0.0f};
    vec3 carry{0.0f};   ///< the low-order part lost by the last additions, to subtract next time
    int32_t count = 0;  ///< an integer: a float count stops at 2^24
};

inline void add_sample(PixelSum& p, vec3 value) {
    const vec3 y = value - p.carry;
    const vec3 t = p.sum + y;
    p.carry = (t - p.sum) - y;
    p.sum = t;
    p.count += 1;
}

/// The mean of the finite samples; 0 when there were none.
inline vec3 pixel_mean(const PixelSum& p) {
    return p.count > 0 ? p.sum / static_cast<float>(p.count) : vec3(0.0f);
}

}  // namespace raylane
