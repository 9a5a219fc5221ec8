// simd: counter-based random numbers on packets; the packet twin of core/rng.h, bit-identical to
// it lane by lane. vint<W> lanes are read as uint32 (wrapping multiplies, logical shifts).
#pragma once

#include <cstdint>

#include "simd/math.h"
#include "simd/simd.h"

namespace raylane::RAYLANE_ISA_NS {

/// rng.h's hash_u32 (Wellons' "lowbias32", 2018) on every lane.
template <int W>
inline vint<W> hash_u32(vint<W> x) {
    x = x ^ shift_right_logical<16>(x);
    x = mul_lo(x, broadcast<W>(0x7feb352du));
    x = x ^ shift_right_logical<15>(x);
    x = mul_lo(x, broadcast<W>(0x846ca68bu));
    x = x ^ shift_right_logical<16>(x);
    return x;
}

/// rng.h's hash_sample on every lane; pass a uniform dim or seed as a broadcast value.
template <int W>
inline vint<W> hash_sample(vint<W> pixel, vint<W> sample, vint<W> dim, vint<W> seed) {
    vint<W> h = hash_u32<W>(seed ^ broadcast<W>(0x9e3779b9u));
    h = hash_u32<W>(h ^ pixel);
    h = hash_u32<W>(h ^ sample);
    h = hash_u32<W>(h ^ dim);
    return h;
}

/// rng.h's random_float on every lane: uniform in [0, 1), the top 24 hash bits times 2^-24.
template <int W>
inline vfloat<W> random_float(vint<W> pixel, vint<W> sample, vint<W> dim, vint<W> seed) {
    const vint<W> top24 = shift_right_logical<8>(hash_sample<W>(pixel, sample, dim, seed));
    return to_float(top24) * vfloat<W>(0x1.0p-24f);
}

}  // namespace raylane::RAYLANE_ISA_NS
