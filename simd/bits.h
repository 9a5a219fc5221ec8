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

/// x^y for x >= 0. W = 1 is std::pow; packets use xsimd's pow (a few ulps from std::pow, so
/// compare the two with a tolerance).
inline float pow(float x, float y) { return std::pow(x, y); }
template <class A>
inline PFloat<A> pow(const PFloat<A>& x, const PFloat<A>& y) {
    return xsimd::pow(x, y);
}

}  // namespace raylane
