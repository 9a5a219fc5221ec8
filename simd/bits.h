// simd: reinterpreting lanes (float <-> int32 bit patterns) and pow, at every width; at W = 1
// the scalar forms are std::bit_cast and std::pow.
#pragma once

#include <bit>
#include <cmath>

#include "simd/simd.h"

namespace raylane {

/// The bit pattern of each float lane as an int32 lane, and back.
inline int32_t as_int(float v) { return std::bit_cast<int32_t>(v); }
inline float as_float(int32_t v) { return std::bit_cast<float>(v); }
template <class A>
inline PInt<A> as_int(const PFloat<A>& v) {
    return xsimd::bitwise_cast<PInt<A>>(v);
}
template <class A>
inline PFloat<A> as_float(const PInt<A>& v) {
    return xsimd::bitwise_cast<PFloat<A>>(v);
}

/// x^y for x > 0. W = 1 is std::pow; packets compute exp2(y log2 x) with xsimd's vectorised
/// exp2 and log2 (relative error about |y log2 x| * 2^-23 from std::pow: compare with a
/// tolerance). x = 0 gives 0 for y > 0.
inline float pow(float x, float y) { return std::pow(x, y); }
template <class A>
inline PFloat<A> pow(const PFloat<A>& x, const PFloat<A>& y) {
    return xsimd::exp2(y * xsimd::log2(x));
}

}  // namespace raylane
