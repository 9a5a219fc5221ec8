// simd: single lanes and whole masks: lane access, active-lane bits, loops over active lanes,
// compaction, masked store and gather. Header-only; the scalar path needs none of it.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "simd/simd.h"

namespace raylane::RAYLANE_ISA_NS {

// ---- lane access ----------------------------------------------------------------------------

/// The lane numbers 0, 1, ..., W - 1.
template <int W>
inline vint<W> lane_index() {
    alignas(64) static constexpr int32_t lanes[16] = {0, 1, 2,  3,  4,  5,  6,  7,
                                                      8, 9, 10, 11, 12, 13, 14, 15};
    return load_aligned<W>(lanes);
}

/// Value of lane i (0 <= i < W). 16- and 8-wide float and int lanes move to lane 0 by a
/// permute in registers (xsimd's batch::get stores the whole register and loads one lane back,
/// which stalls store forwarding when a loop over the lanes repeats it); other types and the
/// 4-wide packets go through memory. (The maskz forms with every lane set: GCC 12 warns that
/// the plain AVX-512 permutes read an undefined register.)
inline float get(float v, int) { return v; }
inline int32_t get(int32_t v, int) { return v; }
inline bool get(bool v, int) { return v; }
template <class T, class A>
inline T get(const xsimd::batch<T, A>& v, int i) {
    [[maybe_unused]] constexpr bool f32 = std::is_same_v<T, float>;
    [[maybe_unused]] constexpr bool i32 = std::is_same_v<T, int32_t>;
    [[maybe_unused]] constexpr std::size_t w = xsimd::batch<T, A>::size;
#if defined(__AVX512F__)
    if constexpr (w == 16 && f32) {
        return _mm512_cvtss_f32(_mm512_maskz_permutexvar_ps(0xffff, _mm512_set1_epi32(i), v));
    } else if constexpr (w == 16 && i32) {  // the bits moved as a float's, unchanged
        const __m512 bits = _mm512_castsi512_ps(v);
        return std::bit_cast<int32_t>(
            _mm512_cvtss_f32(_mm512_maskz_permutexvar_ps(0xffff, _mm512_set1_epi32(i), bits)));
    }
#endif
#if defined(__AVX2__)
    if constexpr (w == 8 && f32) {
        return _mm256_cvtss_f32(_mm256_permutevar8x32_ps(v, _mm256_set1_epi32(i)));
    } else if constexpr (w == 8 && i32) {
        return _mm256_cvtsi256_si32(_mm256_permutevar8x32_epi32(v, _mm256_set1_epi32(i)));
    }
#endif
    return v.get(static_cast<std::size_t>(i));
}
template <class T, class A>
inline bool get(const xsimd::batch_bool<T, A>& m, int i) {
    return m.get(static_cast<std::size_t>(i));
}

/// Loads base[index] for every lane; all indices must be valid (masked form below). The
/// hardware gather instruction where there is one (xsimd 8's batch::gather loads lane by lane).
template <int W>
inline vfloat<W> gather(const float* base, const vint<W>& index) {
    if constexpr (W == 1) {
        return base[index];
    } else {
#if defined(__AVX512F__)
        if constexpr (W == 16) return _mm512_i32gather_ps(index, base, 4);
#endif
#if defined(__AVX2__)
        if constexpr (W == 8) return _mm256_i32gather_ps(base, index, 4);
        if constexpr (W == 4) return _mm_i32gather_ps(base, index, 4);
#endif
        return vfloat<W>::gather(base, index);
    }
}

/// A gather of whole records: out[k] lane i = base[8 * index_i + k] for k = 0 .. 7, the
/// records 32 bytes each (base aligned to 32 bytes; 8 * index must fit in an int32). At W = 16
/// with AVX-512 (F and DQ), 16 loads of 32 bytes and a transposition (a quarter of the loads of
/// eight gathers); elsewhere eight gathers.
template <int W>
inline void gather_records8(const float* base, const vint<W>& index, vfloat<W> (&out)[8]) {
#if defined(__AVX512F__) && defined(__AVX512DQ__)
    if constexpr (W == 16) {
        alignas(64) int32_t at[16];
        index.store_aligned(at);
        // z[i] holds records i and i + 4 (i < 4), z[4 + i] records 8 + i and 12 + i, so that the
        // in-lane transposition below and one 128-bit shuffle leave the lanes in record order
        __m512 z[8];
        for (int i = 0; i < 4; ++i) {
            z[i] = _mm512_insertf32x8(_mm512_castps256_ps512(_mm256_load_ps(base + 8 * at[i])),
                                      _mm256_load_ps(base + 8 * at[i + 4]), 1);
            z[4 + i] =
                _mm512_insertf32x8(_mm512_castps256_ps512(_mm256_load_ps(base + 8 * at[8 + i])),
                                   _mm256_load_ps(base + 8 * at[12 + i]), 1);
        }
        for (int h = 0; h < 8; h += 4) {  // two groups of four registers, 4x4 within each lane
            const __m512 t0 = _mm512_unpacklo_ps(z[h], z[h + 1]);
            const __m512 t1 = _mm512_unpackhi_ps(z[h], z[h + 1]);
            const __m512 t2 = _mm512_unpacklo_ps(z[h + 2], z[h + 3]);
            const __m512 t3 = _mm512_unpackhi_ps(z[h + 2], z[h + 3]);
            z[h] = _mm512_shuffle_ps(t0, t2, 0x44);
            z[h + 1] = _mm512_shuffle_ps(t0, t2, 0xee);
            z[h + 2] = _mm512_shuffle_ps(t1, t3, 0x44);
            z[h + 3] = _mm512_shuffle_ps(t1, t3, 0xee);
        }
        // 128-bit lane j of z[k] (k < 4) is field k (j even) or k + 4 (j odd) of records
        // 0-3, 0-3, 4-7, 4-7 ... (j = 0, 1, 2, 3); z[4 + k] likewise for records 8-15
        for (int k = 0; k < 4; ++k) {
            out[k] = _mm512_shuffle_f32x4(z[k], z[4 + k], 0x88);      // lanes 0, 2 | 0, 2
            out[k + 4] = _mm512_shuffle_f32x4(z[k], z[4 + k], 0xdd);  // lanes 1, 3 | 1, 3
        }
        return;
    }
#endif
    const vint<W> at = index * vint<W>(8);
    for (int k = 0; k < 8; ++k) out[k] = gather<W>(base + k, at);
}

/// Sets lane i of v to x (0 <= i < W); the other lanes keep their values.
inline void set(float& v, int, float x) { v = x; }
inline void set(int32_t& v, int, int32_t x) { v = x; }
template <class T, class A>
inline void set(xsimd::batch<T, A>& v, int i, T x) {
    constexpr int w = width_of<xsimd::batch<T, A>>;
    v = select(eq(lane_index<w>(), PInt<A>(i)), xsimd::batch<T, A>(x), v);
}

// ---- mask queries ---------------------------------------------------------------------------

/// The mask as an integer: bit i is lane i (bits above W are zero).
inline uint32_t bits(bool m) { return m ? 1u : 0u; }
template <class A>
inline uint32_t bits(const PMask<A>& m) {
    constexpr int w = width_of<PMask<A>>;
    if constexpr (w == 16) {
        return static_cast<uint32_t>(static_cast<typename PMask<A>::register_type>(m));
    } else if constexpr (w == 8) {
        return static_cast<uint32_t>(_mm256_movemask_ps(m));
    } else {
        static_assert(w == 4);
        return static_cast<uint32_t>(_mm_movemask_ps(m));
    }
}

/// The mask whose lane i is bit i of b (bits at and above W are ignored).
template <int W>
inline vmask<W> mask_from_bits(uint32_t b) {
    if constexpr (W == 1) {
        return (b & 1u) != 0;
    } else if constexpr (W == 16) {
        return vmask<W>(static_cast<typename vmask<W>::register_type>(b));
    } else {
        alignas(64) static constexpr int32_t lane_bits[16] = {
            1 << 0, 1 << 1, 1 << 2,  1 << 3,  1 << 4,  1 << 5,  1 << 6,  1 << 7,
            1 << 8, 1 << 9, 1 << 10, 1 << 11, 1 << 12, 1 << 13, 1 << 14, 1 << 15};
        const vint<W> lane_bit = load_aligned<W>(lane_bits);
        return eq(vint<W>(static_cast<int32_t>(b)) & lane_bit, lane_bit);
    }
}

/// Lanes 0 .. n - 1 active, the others not (0 <= n <= W): the valid lanes of a loop's last,
/// partial packet.
template <int W>
inline vmask<W> prefix_mask(int n) {
    return mask_from_bits<W>((1u << n) - 1u);
}

/// Whether any / all / no lanes are active, and how many are.
inline bool any(bool m) { return m; }
inline bool all(bool m) { return m; }
inline bool none(bool m) { return !m; }
template <class A>
inline bool any(const PMask<A>& m) {
    return xsimd::any(m);
}
template <class A>
inline bool all(const PMask<A>& m) {
    return xsimd::all(m);
}
template <class A>
inline bool none(const PMask<A>& m) {
    return !xsimd::any(m);
}
template <AnyMask M>
inline int count(const M& m) {
    return std::popcount(bits(m));
}

/// The lowest active lane, or -1 when no lane is active.
template <AnyMask M>
inline int first_active(const M& m) {
    const uint32_t b = bits(m);
    return b == 0 ? -1 : std::countr_zero(b);
}

/// The first n active lanes of m (in lane order); all of them when m has no more than n.
template <AnyMask M>
inline M keep_first_active(const M& m, uint32_t n) {
    uint32_t b = bits(m);
    if (static_cast<uint32_t>(std::popcount(b)) <= n) return m;
#if defined(__BMI2__)
    b = _pdep_u32((1u << n) - 1u, b);  // n < popcount(b) <= 16: the low n set bits of b
#else
    uint32_t kept = 0;
    for (; n > 0; --n, b &= b - 1) kept |= b & (0u - b);  // the lowest set bit, n times
    b = kept;
#endif
    return mask_from_bits<width_of<M>>(b);
}

/// Calls f(lane) for each active lane in increasing lane order (lane is an int).
template <AnyMask M, class F>
inline void for_each_active(const M& m, F&& f) {
    for (uint32_t b = bits(m); b != 0; b &= b - 1) f(std::countr_zero(b));
}

// ---- compaction -----------------------------------------------------------------------------

namespace simd_detail {
/// Portable compaction through memory, on the lanes' bits: active lanes to the front, zeros after.
template <class A>
inline PInt<A> compact_by_loop(const PInt<A>& v, uint32_t b) {
    constexpr int w = width_of<PInt<A>>;
    alignas(64) int32_t in[w];
    alignas(64) int32_t out[w] = {};
    v.store_aligned(in);
    int n = 0;
    for (int i = 0; i < w; ++i) {
        const uint32_t active = (b >> i) & 1u;
        out[n] = active ? in[i] : 0;  // an inactive lane's write is overwritten or stays 0
        n += static_cast<int>(active);
    }
    return PInt<A>::load_aligned(out);
}

/// Writes the active lanes of v (as 32-bit patterns) to p[lane]; other lanes' memory untouched.
template <class A>
inline void store_active_bits(void* p, const PFloat<A>& v, const PMask<A>& m) {
    [[maybe_unused]] constexpr int w = width_of<PFloat<A>>;
#if defined(__AVX512F__)
    if constexpr (w == 16) return _mm512_mask_storeu_ps(p, static_cast<__mmask16>(m), v);
#endif
#if defined(__AVX512F__) && defined(__AVX512VL__)
    if constexpr (w == 8) return _mm256_mask_storeu_ps(p, static_cast<__mmask8>(bits(m)), v);
    if constexpr (w == 4) return _mm_mask_storeu_ps(p, static_cast<__mmask8>(bits(m)), v);
#elif defined(__AVX__)
    if constexpr (w == 8)
        return _mm256_maskstore_ps(static_cast<float*>(p), _mm256_castps_si256(m), v);
    if constexpr (w == 4) return _mm_maskstore_ps(static_cast<float*>(p), _mm_castps_si128(m), v);
#endif
    alignas(64) float lanes[w];
    v.store_aligned(lanes);
    for_each_active(m, [&](int i) { std::memcpy(static_cast<char*>(p) + 4 * i, &lanes[i], 4); });
}
}  // namespace simd_detail

/// The active lanes' values moved to lanes 0 .. count(m) - 1 in lane order; other lanes are 0.
/// AVX-512 uses vcompressps (W = 4, 8 too with AVX-512VL); AVX2 + BMI2 at W = 8 a pext-built
/// permutation; otherwise a loop through memory.
inline float compact(float v, bool m) { return m ? v : 0.0f; }
inline int32_t compact(int32_t v, bool m) { return m ? v : 0; }
template <class A>
inline PFloat<A> compact(const PFloat<A>& v, const PMask<A>& m) {
    [[maybe_unused]] constexpr int w = width_of<PFloat<A>>;
    const uint32_t b = bits(m);
#if defined(__AVX512F__)
    if constexpr (w == 16) return _mm512_maskz_compress_ps(static_cast<__mmask16>(b), v);
#endif
#if defined(__AVX512F__) && defined(__AVX512VL__)
    if constexpr (w == 8) return _mm256_maskz_compress_ps(static_cast<__mmask8>(b), v);
    if constexpr (w == 4) return _mm_maskz_compress_ps(static_cast<__mmask8>(b), v);
#elif defined(__AVX2__) && defined(__BMI2__)
    if constexpr (w == 8) {
        // Byte k of `wanted` is the source lane of output lane k (zero past the active count).
        const uint64_t spread = _pdep_u64(b, 0x0101010101010101ull) * 0xffu;
        const uint64_t wanted = _pext_u64(0x0706050403020100ull, spread);
        const __m256i perm = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<int64_t>(wanted)));
        const __m256 moved = _mm256_permutevar8x32_ps(v, perm);
        return select(mask_from_bits<8>((1u << std::popcount(b)) - 1u), PFloat<A>(moved),
                      PFloat<A>(0.0f));
    }
#endif
    return int_as_float(simd_detail::compact_by_loop(float_as_int(v), b));
}
template <class A>
inline PInt<A> compact(const PInt<A>& v, const PMask<A>& m) {
    return float_as_int(compact(int_as_float(v), m));
}

/// Writes v at p[i] for the active lanes i only; inactive lanes' memory is not touched.
inline void store(float* p, float v, bool m) {
    if (m) *p = v;
}
inline void store(int32_t* p, int32_t v, bool m) {
    if (m) *p = v;
}
template <class A>
inline void store(float* p, const PFloat<A>& v, const PMask<A>& m) {
    simd_detail::store_active_bits(p, v, m);
}
template <class A>
inline void store(int32_t* p, const PInt<A>& v, const PMask<A>& m) {
    simd_detail::store_active_bits(p, int_as_float(v), m);
}

/// Writes the active lanes' values to out[0 .. n) in lane order and returns n = count(m).
/// Exactly n elements are written, so out needs room for n, not W.
template <AnyFloat V, AnyMask M>
inline int compress_store(float* out, const V& v, const M& m) {
    const int n = count(m);
    store(out, compact(v, m), mask_from_bits<width_of<V>>((1u << n) - 1u));
    return n;
}
template <AnyInt V, AnyMask M>
inline int compress_store(int32_t* out, const V& v, const M& m) {
    const int n = count(m);
    store(out, compact(v, m), mask_from_bits<width_of<V>>((1u << n) - 1u));
    return n;
}

/// base[index] for the active lanes, 0 for the others; inactive lanes' indices are never read,
/// so they may hold garbage.
inline float gather(const float* base, int32_t index, bool m) { return m ? base[index] : 0.0f; }
template <class A>
inline PFloat<A> gather(const float* base, const PInt<A>& index, const PMask<A>& m) {
    constexpr int w = width_of<PFloat<A>>;
#if defined(__AVX512F__)
    if constexpr (w == 16) {
        return _mm512_mask_i32gather_ps(_mm512_setzero_ps(), static_cast<__mmask16>(m), index, base,
                                        4);
    }
#endif
#if defined(__AVX2__)
    if constexpr (w == 8) return _mm256_mask_i32gather_ps(_mm256_setzero_ps(), base, index, m, 4);
    if constexpr (w == 4) return _mm_mask_i32gather_ps(_mm_setzero_ps(), base, index, m, 4);
#endif
    alignas(64) float out[w] = {};
    for_each_active(m, [&](int i) { out[i] = base[get(index, i)]; });
    return PFloat<A>::load_aligned(out);
}

}  // namespace raylane::RAYLANE_ISA_NS
