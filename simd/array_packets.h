// simd: arrays walked a packet at a time: the last, partial packet's masked load, byte gathers
// by index, and whether compaction (lanes.h) is native, which decides if such a loop pays.
#pragma once

#include <cstdint>
#include <cstring>

#include "simd/lanes.h"
#include "simd/simd.h"

namespace raylane::RAYLANE_ISA_NS {

/// True when compact, compress_store, the masked load and store and gather_u8 are single
/// instructions at width W: AVX-512 (with AVX-512VL at W = 4 and 8). Elsewhere they go lane by
/// lane through memory (SSE) or through permutes, mask stores and gathers (AVX2), and a loop that
/// compacts a packet at a time can then lose to a branch-free scalar loop (the BVH build's splits
/// do: bench_build times them per set).
template <int W>
inline constexpr bool compaction_is_native =
#if defined(__AVX512F__) && defined(__AVX512VL__)
    W == 4 || W == 8 || W == 16;
#elif defined(__AVX512F__)
    W == 16;
#else
    false;
#endif

// ---- masked load ------------------------------------------------------------------------------

namespace simd_detail {
/// Reads the active lanes (as 32-bit patterns) from p[lane], 0 for the others; other lanes'
/// memory is never read.
template <class A>
inline PFloat<A> load_active_bits(const void* p, const PMask<A>& m) {
    [[maybe_unused]] constexpr int w = width_of<PFloat<A>>;
#if defined(__AVX512F__)
    if constexpr (w == 16) return _mm512_maskz_loadu_ps(static_cast<__mmask16>(m), p);
#endif
#if defined(__AVX512F__) && defined(__AVX512VL__)
    if constexpr (w == 8) return _mm256_maskz_loadu_ps(static_cast<__mmask8>(bits(m)), p);
    if constexpr (w == 4) return _mm_maskz_loadu_ps(static_cast<__mmask8>(bits(m)), p);
#elif defined(__AVX__)
    if constexpr (w == 8)
        return _mm256_maskload_ps(static_cast<const float*>(p), _mm256_castps_si256(m));
    if constexpr (w == 4) return _mm_maskload_ps(static_cast<const float*>(p), _mm_castps_si128(m));
#endif
    alignas(64) float lanes[w] = {};
    for_each_active(m,
                    [&](int i) { std::memcpy(&lanes[i], static_cast<const char*>(p) + 4 * i, 4); });
    return PFloat<A>::load_aligned(lanes);
}
}  // namespace simd_detail

/// Reads p[i] for the active lanes i, 0 for the others; inactive lanes' memory is never read, so
/// it may lie past the end of an array (the last, partial packet of a loop).
inline float load(const float* p, bool m) { return m ? *p : 0.0f; }
inline int32_t load(const int32_t* p, bool m) { return m ? *p : 0; }
template <class A>
inline PFloat<A> load(const float* p, const PMask<A>& m) {
    return simd_detail::load_active_bits(p, m);
}
template <class A>
inline PInt<A> load(const int32_t* p, const PMask<A>& m) {
    return float_as_int(simd_detail::load_active_bits(p, m));
}

// ---- byte gather ------------------------------------------------------------------------------

/// Bytes that gather_u8 may read past an active lane's byte: an array it gathers from needs this
/// many readable bytes after its end.
inline constexpr int gather_u8_padding = 3;

/// base[index], a byte zero-extended, for the active lanes; 0 for the others, whose indices are
/// never read. The gather instructions (AVX2, AVX-512) read the 4 bytes from base + index and keep
/// the low one, so the gather_u8_padding bytes after every active lane's byte must be readable.
inline int32_t gather_u8(const uint8_t* base, int32_t index, bool m) { return m ? base[index] : 0; }
template <class A>
inline PInt<A> gather_u8(const uint8_t* base, const PInt<A>& index, const PMask<A>& m) {
    constexpr int w = width_of<PInt<A>>;
    [[maybe_unused]] const PInt<A> low_byte(0xff);
#if defined(__AVX512F__)
    if constexpr (w == 16) {
        return PInt<A>(_mm512_mask_i32gather_epi32(_mm512_setzero_si512(),
                                                   static_cast<__mmask16>(m), index, base, 1)) &
               low_byte;
    }
#endif
#if defined(__AVX2__)
    [[maybe_unused]] const int* at = reinterpret_cast<const int*>(base);  // bytes are read
    if constexpr (w == 8) {
        return PInt<A>(_mm256_mask_i32gather_epi32(_mm256_setzero_si256(), at, index,
                                                   _mm256_castps_si256(m), 1)) &
               low_byte;
    }
    if constexpr (w == 4) {
        return PInt<A>(_mm_mask_i32gather_epi32(_mm_setzero_si128(), at, index, _mm_castps_si128(m),
                                                1)) &
               low_byte;
    }
#endif
    alignas(64) int32_t out[w] = {};
    for_each_active(m, [&](int i) { out[i] = base[get(index, i)]; });
    return PInt<A>::load_aligned(out);
}

}  // namespace raylane::RAYLANE_ISA_NS
