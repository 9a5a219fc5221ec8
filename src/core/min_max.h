// core: min and max of two floats in the order of SSE's minps / maxps, for the reference path.
#pragma once

namespace raylane {

/// a < b ? a : b and a > b ? a : b: b when either is NaN, the NaN order of _mm_min_ps /
/// _mm_max_ps, which the packet path gets from simd/math.h's min and max.
inline float min_of(float a, float b) { return a < b ? a : b; }
inline float max_of(float a, float b) { return a > b ? a : b; }

}  // namespace raylane
