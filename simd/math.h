// simd: lane arithmetic with one defined behaviour at every W, where xsimd 8.1 lacks it or differs
// from float / uint32 (min/max NaN order, neg, wrapping ints, uint32 min/max, fma, reciprocals,
// reductions).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "simd/simd.h"

namespace raylane::RAYLANE_ISA_NS {

// ---- basic float functions ------------------------------------------------------------------

/// min(a, b) = a < b ? a : b, i.e. _mm_min_ps(a, b): b when either is NaN, b for -0.0 vs +0.0.
/// max(a, b) = a > b ? a : b, i.e. _mm_max_ps(a, b). Identical at every W (numerics.md §0.3).
inline float min(float a, float b) { return a < b ? a : b; }
inline float max(float a, float b) { return a > b ? a : b; }
template <class A>
inline PFloat<A> min(const PFloat<A>& a, const PFloat<A>& b) {
    return xsimd::min(a, b);
}
template <class A>
inline PFloat<A> max(const PFloat<A>& a, const PFloat<A>& b) {
    return xsimd::max(a, b);
}

/// |v| by clearing the sign bit (NaN stays NaN with its payload).
inline float abs(float v) { return std::fabs(v); }
template <class A>
inline PFloat<A> abs(const PFloat<A>& v) {
    return xsimd::abs(v);
}

/// Correctly rounded square root; NaN for negative inputs, -0.0 for -0.0.
inline float sqrt(float v) { return std::sqrt(v); }
template <class A>
inline PFloat<A> sqrt(const PFloat<A>& v) {
    return xsimd::sqrt(v);
}

/// cos and sin in radians: std:: lane by lane at every W (map_lanes below), so that every
/// instruction set and both paths get the same bits (a vectorised approximation rounds
/// differently with and without FMA).
inline float cos(float v) { return std::cos(v); }
template <class A>
inline PFloat<A> cos(const PFloat<A>& v);
inline float sin(float v) { return std::sin(v); }
template <class A>
inline PFloat<A> sin(const PFloat<A>& v);

/// -v by flipping the sign bit, at every W: neg(+0) = -0, and NaN changes sign too.
inline float neg(float v) { return -v; }
template <class A>
inline PFloat<A> neg(const PFloat<A>& v) {
    return v ^ PFloat<A>(-0.0f);
}

/// a != b as C++ defines it for float: true when either is NaN.
inline bool ne(float a, float b) { return a != b; }
template <class A>
inline PMask<A> ne(const PFloat<A>& a, const PFloat<A>& b) {
    return ~(a == b);
}

/// True where v is NaN.
inline bool is_nan(float v) { return v != v; }
template <class A>
inline PMask<A> is_nan(const PFloat<A>& v) {
    return ~(v == v);
}

// ---- lane by lane ---------------------------------------------------------------------------

/// f (a scalar float function, e.g. std::cos) applied to every lane in turn: the scalar path's
/// bits at every W and under every instruction set, where a vector approximation (xsimd's cos,
/// sin, exp) rounds differently with and without FMA.
template <class F>
inline float map_lanes(float v, F f) {
    return f(v);
}
template <class A, class F>
inline PFloat<A> map_lanes(const PFloat<A>& v, F f) {
    constexpr size_t n = PFloat<A>::size;
    alignas(64) float lanes[n];
    v.store_aligned(lanes);
    for (size_t i = 0; i < n; ++i) lanes[i] = f(lanes[i]);
    return PFloat<A>::load_aligned(lanes);
}

template <class A>
inline PFloat<A> cos(const PFloat<A>& v) {
    return map_lanes(v, [](float x) { return std::cos(x); });
}
template <class A>
inline PFloat<A> sin(const PFloat<A>& v) {
    return map_lanes(v, [](float x) { return std::sin(x); });
}

// ---- int32 arithmetic -----------------------------------------------------------------------
// Lanes read as uint32: results wrap modulo 2^32 at every W (never signed overflow at W = 1).

/// a + b and the low 32 bits of a * b, modulo 2^32.
inline int32_t add(int32_t a, int32_t b) {
    return static_cast<int32_t>(static_cast<uint32_t>(a) + static_cast<uint32_t>(b));
}
inline int32_t mul_lo(int32_t a, int32_t b) {
    return static_cast<int32_t>(static_cast<uint32_t>(a) * static_cast<uint32_t>(b));
}
template <class A>
inline PInt<A> add(const PInt<A>& a, const PInt<A>& b) {
    return a + b;
}
template <class A>
inline PInt<A> mul_lo(const PInt<A>& a, const PInt<A>& b) {
    return a * b;
}

/// Shifts by a constant 0 <= K < 32: left, right logical (zeros in; uint32), right arithmetic.
template <int K>
inline int32_t shift_left(int32_t v) {
    return static_cast<int32_t>(static_cast<uint32_t>(v) << K);
}
template <int K>
inline int32_t shift_right_logical(int32_t v) {
    return static_cast<int32_t>(static_cast<uint32_t>(v) >> K);
}
template <int K>
inline int32_t shift_right_arith(int32_t v) {
    return v >> K;
}
template <int K, class A>
inline PInt<A> shift_left(const PInt<A>& v) {
    return v << K;
}
template <int K, class A>
inline PInt<A> shift_right_logical(const PInt<A>& v) {
    using U = xsimd::batch<uint32_t, A>;
    return xsimd::bitwise_cast<PInt<A>>(xsimd::bitwise_cast<U>(v) >> K);
}
template <int K, class A>
inline PInt<A> shift_right_arith(const PInt<A>& v) {
    return v >> K;
}

// ---- uint32 order ----------------------------------------------------------------------------
// Int lanes read as uint32 (sort keys, ids): lane-wise min and max, on every lane or on the
// active ones, and the smallest and largest lane.

/// The smaller and the larger of a and b as uint32, lane by lane.
inline int32_t min_u32(int32_t a, int32_t b) { return lt_u32(a, b) ? a : b; }
inline int32_t max_u32(int32_t a, int32_t b) { return lt_u32(a, b) ? b : a; }
template <class A>
inline PInt<A> min_u32(const PInt<A>& a, const PInt<A>& b) {
    [[maybe_unused]] constexpr int w = width_of<PInt<A>>;
#if defined(__AVX512F__)
    if constexpr (w == 16) return _mm512_min_epu32(a, b);
#endif
#if defined(__AVX2__)
    if constexpr (w == 8) return _mm256_min_epu32(a, b);
#endif
#if defined(__SSE4_1__)
    if constexpr (w == 4) return _mm_min_epu32(a, b);
#endif
    return select(lt_u32(a, b), a, b);
}
template <class A>
inline PInt<A> max_u32(const PInt<A>& a, const PInt<A>& b) {
    [[maybe_unused]] constexpr int w = width_of<PInt<A>>;
#if defined(__AVX512F__)
    if constexpr (w == 16) return _mm512_max_epu32(a, b);
#endif
#if defined(__AVX2__)
    if constexpr (w == 8) return _mm256_max_epu32(a, b);
#endif
#if defined(__SSE4_1__)
    if constexpr (w == 4) return _mm_max_epu32(a, b);
#endif
    return select(lt_u32(a, b), b, a);
}

/// min_u32 / max_u32 on the active lanes; inactive lanes keep a (a running bound that only the
/// active lanes move).
inline int32_t min_u32(int32_t a, int32_t b, bool m) { return m ? min_u32(a, b) : a; }
inline int32_t max_u32(int32_t a, int32_t b, bool m) { return m ? max_u32(a, b) : a; }
template <class A>
inline PInt<A> min_u32(const PInt<A>& a, const PInt<A>& b, const PMask<A>& m) {
#if defined(__AVX512F__)
    if constexpr (width_of<PInt<A>> == 16)
        return _mm512_mask_min_epu32(a, static_cast<__mmask16>(m), a, b);
#endif
    return select(m, min_u32(a, b), a);
}
template <class A>
inline PInt<A> max_u32(const PInt<A>& a, const PInt<A>& b, const PMask<A>& m) {
#if defined(__AVX512F__)
    if constexpr (width_of<PInt<A>> == 16)
        return _mm512_mask_max_epu32(a, static_cast<__mmask16>(m), a, b);
#endif
    return select(m, max_u32(a, b), a);
}

/// The smallest and the largest lane as uint32 (every lane counts). Through memory: for the end
/// of a loop, not its body (GCC 12's _mm512_reduce_min_epu32 warns of an uninitialised variable).
inline uint32_t hmin_u32(int32_t v) { return static_cast<uint32_t>(v); }
inline uint32_t hmax_u32(int32_t v) { return static_cast<uint32_t>(v); }
template <class A>
inline uint32_t hmin_u32(const PInt<A>& v) {
    constexpr int w = width_of<PInt<A>>;
    alignas(64) int32_t lanes[w];
    v.store_aligned(lanes);
    uint32_t m = static_cast<uint32_t>(lanes[0]);
    for (int i = 1; i < w; ++i) {
        const uint32_t x = static_cast<uint32_t>(lanes[i]);
        m = x < m ? x : m;
    }
    return m;
}
template <class A>
inline uint32_t hmax_u32(const PInt<A>& v) {
    constexpr int w = width_of<PInt<A>>;
    alignas(64) int32_t lanes[w];
    v.store_aligned(lanes);
    uint32_t m = static_cast<uint32_t>(lanes[0]);
    for (int i = 1; i < w; ++i) {
        const uint32_t x = static_cast<uint32_t>(lanes[i]);
        m = x > m ? x : m;
    }
    return m;
}

// ---- fused multiply-add ---------------------------------------------------------------------

/// a * b + c with a single rounding, at every width (std::fma at W = 1). Never contracted or
/// split: the project builds with -ffp-contract=off (numerics.md §0.2), so an FMA happens only
/// where this is called. Without an FMA unit (x86-64-v2) each lane calls std::fma: slow, exact.
inline float fma(float a, float b, float c) { return std::fma(a, b, c); }
template <class A>
inline PFloat<A> fma(const PFloat<A>& a, const PFloat<A>& b, const PFloat<A>& c) {
    constexpr int w = width_of<PFloat<A>>;
#if defined(__AVX512F__)
    if constexpr (w == 16) return _mm512_fmadd_ps(a, b, c);
#endif
#if defined(__FMA__)
    if constexpr (w == 8) return _mm256_fmadd_ps(a, b, c);
    if constexpr (w == 4) return _mm_fmadd_ps(a, b, c);
#endif
    alignas(64) float x[w], y[w], z[w];
    a.store_aligned(x);
    b.store_aligned(y);
    c.store_aligned(z);
    for (int i = 0; i < w; ++i) x[i] = std::fma(x[i], y[i], z[i]);
    return PFloat<A>::load_aligned(x);
}

// ---- reciprocals ----------------------------------------------------------------------------

/// 1 / v by IEEE division: correctly rounded, identical at every width. Use it for ray
/// directions (numerics.md §0.2): 1 / ±0 = ±inf, 1 / ±inf = ±0.
inline float rcp_exact(float v) { return 1.0f / v; }
template <class A>
inline PFloat<A> rcp_exact(const PFloat<A>& v) {
    return PFloat<A>(1.0f) / v;
}

/// Approximate 1 / v: the rcp instruction (12 bits; 14 with AVX-512) and one Newton-Raphson step
/// r' = r (2 - v r). NOT bit-exact, and the rcp bits differ between CPU vendors: relative error
/// below 2^-21 for normal v whose reciprocal is normal. ±0 -> ±inf and ±inf -> ±0 like
/// rcp_exact; never use it where a robustness argument needs correct rounding.
inline float rcp_refined(float v) {
#if defined(__SSE__)
    const float r = _mm_cvtss_f32(_mm_rcp_ss(_mm_set_ss(v)));
#else
    const float r = 1.0f / v;
#endif
    const float refined = r * (2.0f - v * r);
    return is_nan(refined) ? r : refined;  // v = ±0 or ±inf: 0 * inf in the step
}
namespace simd_detail {
template <class A>
inline PFloat<A> rcp_approx(const PFloat<A>& v) {
    constexpr int w = width_of<PFloat<A>>;
    if constexpr (w == 16) {
        return _mm512_rcp14_ps(v);
    } else if constexpr (w == 8) {
        return _mm256_rcp_ps(v);
    } else {
        return _mm_rcp_ps(v);
    }
}
}  // namespace simd_detail
template <class A>
inline PFloat<A> rcp_refined(const PFloat<A>& v) {
    const PFloat<A> r = simd_detail::rcp_approx(v);
    const PFloat<A> refined = r * (PFloat<A>(2.0f) - v * r);
    return select(is_nan(refined), r, refined);
}

// ---- sign bits ------------------------------------------------------------------------------

/// True where the sign bit is set: negative numbers, -0.0, -inf and NaNs with the sign bit.
inline bool sign_bit(float v) { return std::signbit(v); }
template <class A>
inline PMask<A> sign_bit(const PFloat<A>& v) {
    return lt(float_as_int(v), PInt<A>(0));
}

/// The magnitude of a with the sign bit of s (std::copysign).
inline float copysign(float a, float s) { return std::copysign(a, s); }
template <class A>
inline PFloat<A> copysign(const PFloat<A>& a, const PFloat<A>& s) {
    return xsimd::copysign(a, s);
}

/// a with its sign flipped where s has the sign bit set: a * sign(s) without a multiply
/// (exact for every a, including NaN, inf and ±0).
inline float mul_sign(float a, float s) {
    const int32_t sign = float_as_int(s) & std::numeric_limits<int32_t>::min();
    return int_as_float(float_as_int(a) ^ sign);
}
template <class A>
inline PFloat<A> mul_sign(const PFloat<A>& a, const PFloat<A>& s) {
    const PInt<A> sign = float_as_int(s) & PInt<A>(std::numeric_limits<int32_t>::min());
    return int_as_float(float_as_int(a) ^ sign);
}

// ---- horizontal reductions ------------------------------------------------------------------
// Inactive lanes never reach the result (numerics.md §0.3). NaN lanes are skipped by hmin and
// hmax; when -0.0 and +0.0 tie for the minimum, either may be returned.

namespace simd_detail {
template <class A>
inline float reduce_min(const PFloat<A>& v) {
    constexpr int w = width_of<PFloat<A>>;
    if constexpr (w == 16) {
        return _mm512_reduce_min_ps(v);
    } else if constexpr (w == 8) {
        __m128 m = _mm_min_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
        m = _mm_min_ps(m, _mm_movehl_ps(m, m));
        return _mm_cvtss_f32(_mm_min_ss(m, _mm_shuffle_ps(m, m, 1)));
    } else {
        const __m128 m = _mm_min_ps(v, _mm_movehl_ps(v, v));
        return _mm_cvtss_f32(_mm_min_ss(m, _mm_shuffle_ps(m, m, 1)));
    }
}
}  // namespace simd_detail

/// Smallest active, non-NaN lane; +inf when there is none.
inline float hmin(float v, bool m) {
    return m && !is_nan(v) ? v : std::numeric_limits<float>::infinity();
}
template <class A>
inline float hmin(const PFloat<A>& v, const PMask<A>& m) {
    const PFloat<A> inf(std::numeric_limits<float>::infinity());
    return simd_detail::reduce_min(select(mask_andnot(m, is_nan(v)), v, inf));
}

/// Largest active, non-NaN lane; -inf when there is none.
inline float hmax(float v, bool m) {
    return m && !is_nan(v) ? v : -std::numeric_limits<float>::infinity();
}
template <class A>
inline float hmax(const PFloat<A>& v, const PMask<A>& m) {
    const PFloat<A> neg_inf(-std::numeric_limits<float>::infinity());
    return -simd_detail::reduce_min(neg(select(mask_andnot(m, is_nan(v)), v, neg_inf)));
}

/// Sum of the active lanes (0 when none), added in an unspecified order: compare the result
/// with a tolerance, or use values whose sums are exact.
inline float hsum(float v, bool m) { return m ? v : 0.0f; }
template <class A>
inline float hsum(const PFloat<A>& v, const PMask<A>& m) {
    return xsimd::hadd(select(m, v, PFloat<A>(0.0f)));
}

/// x^y: std::pow lane by lane at every W, the same bits under every instruction set and in both
/// paths. x = 0 gives 0 for y > 0.
inline float pow(float x, float y) { return std::pow(x, y); }
template <class A>
inline PFloat<A> pow(const PFloat<A>& x, const PFloat<A>& y) {
    constexpr size_t n = PFloat<A>::size;
    alignas(64) float xs[n], ys[n];
    x.store_aligned(xs), y.store_aligned(ys);
    for (size_t i = 0; i < n; ++i) xs[i] = std::pow(xs[i], ys[i]);
    return PFloat<A>::load_aligned(xs);
}

/// The unmasked forms: every lane counts.
template <AnyFloat V>
inline float hmin(const V& v) {
    return hmin(v, vmask<width_of<V>>(true));
}
template <AnyFloat V>
inline float hmax(const V& v) {
    return hmax(v, vmask<width_of<V>>(true));
}
template <AnyFloat V>
inline float hsum(const V& v) {
    return hsum(v, vmask<width_of<V>>(true));
}

}  // namespace raylane::RAYLANE_ISA_NS
