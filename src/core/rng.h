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

/// The seed of an animation's frame `frame`: `seed` itself for frame 0 (a still renders as it
/// always has), else a hash of both, so that frames draw different numbers and frame k is the
/// same image whoever renders it.
inline uint32_t frame_seed(uint32_t seed, int frame) {
    if (frame == 0) return seed;
    return hash_u32(seed ^ hash_u32(static_cast<uint32_t>(frame) ^ 0x2545f491u));
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

/// What a random number at a hit is for (the `purpose` of path_dim and child_key).
enum Purpose : uint32_t {
    purpose_light = 1,    ///< index = light << 16 | sample, coord 0..2
    purpose_glossy = 2,   ///< index = glossy ray, coord 0..1
    purpose_mirror = 3,   ///< child key of a mirror ray
    purpose_reflect = 4,  ///< child key of a glass reflection
    purpose_refract = 5,  ///< child key of a refracted ray
};

/// The key of a child ray in the path tree (the camera ray has key 0). Both paths derive every
/// random number at a hit from its ray's key, so a path draws the same numbers in either.
inline uint32_t child_key(uint32_t parent, uint32_t purpose, uint32_t index) {
    return hash_u32(parent ^ hash_u32((purpose << 28) ^ index ^ 0x68e31da4u));
}

/// The sample dimension of random number `coord` for (purpose, index) at the hit of ray `key`.
/// The top bit is set, so it never collides with the camera's dimensions (0 to 3).
inline uint32_t path_dim(uint32_t key, uint32_t purpose, uint32_t index, uint32_t coord) {
    return hash_u32(key ^ hash_u32((purpose << 28) ^ (index << 2) ^ coord)) | 0x80000000u;
}

}  // namespace raylane
