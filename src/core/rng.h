// core: counter-based random numbers. Every sample derives from (pixel, sample, dimension, seed)
// so images do not depend on thread count or tile order. The packet twin is in simd/hash.h.
#pragma once

#include <cstdint>

namespace raylane {

/// A 32-bit integer finaliser (Chris Wellons' "lowbias32", 2018): xor-shift-multiply rounds
/// with good avalanche. Only 32-bit multiplies, xors and shifts, so the packet form is exact.
inline uint32_t hash_u32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

/// Hash of the four counters; each step mixes one counter into the running state.
inline uint32_t hash_sample(uint32_t pixel, uint32_t sample, uint32_t dim, uint32_t seed) {
    uint32_t h = hash_u32(seed ^ 0x9e3779b9u);
    h = hash_u32(h ^ pixel);
    h = hash_u32(h ^ sample);
    h = hash_u32(h ^ dim);
    return h;
}

/// Uniform float in [0, 1): the top 24 bits of the hash times 2^-24.
inline float random_float(uint32_t pixel, uint32_t sample, uint32_t dim, uint32_t seed) {
    return static_cast<float>(hash_sample(pixel, sample, dim, seed) >> 8) * 0x1.0p-24f;
}

/// Sample dimensions in use, so no two consumers draw the same numbers.
enum SampleDim : uint32_t {
    dim_pixel_x = 0,
    dim_pixel_y = 1,
    dim_lens_u = 2,
    dim_lens_v = 3,
    dim_first_free = 4,
};

}  // namespace raylane
