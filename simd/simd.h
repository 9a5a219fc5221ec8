// simd: the packet vocabulary every *_packet kernel is written in (header-only, over xsimd 8.1).
// The scalar reference path uses plain float / int32_t / bool, which is exactly what W == 1 is.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "simd/namespace.h"

// GCC 12's AVX-512 intrinsics (_mm512_undefined_ps: "__m512 __Y = __Y;") warn -W[maybe-]
// uninitialized wherever they are inlined (GCC bug 105593, fixed in 12.3). The warning points into
// these headers, so silencing it around their first inclusion keeps -Werror builds clean.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#if !defined(__clang__)  // a GCC warning (Clang has no such group)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <immintrin.h>

#include <xsimd/xsimd.hpp>
#pragma GCC diagnostic pop

namespace raylane::RAYLANE_ISA_NS {

// ---- widths --------------------------------------------------------------------------------

/// The packet width of this instruction set's copy of the code: 16 (avx512), 8 (avx2), 4 (sse4.2).
#if defined(__AVX512F__)
inline constexpr int native_width = 16;
#elif defined(__AVX2__) && defined(__FMA__)
inline constexpr int native_width = 8;
#elif defined(__SSE4_2__) || defined(__SSE2__)
inline constexpr int native_width = 4;
#else
inline constexpr int native_width = 1;
#endif

/// X(W) for each width this set's code is instantiated at (the explicit instantiations of the
/// .cpp files, the typed tests): sse4.2: 1 (the scalar width, for the tests) and 4; avx2: 8;
/// avx512: 16, and 8 (its 8-wide leaf and node tests, tested on their own).
#if defined(__AVX512F__)
#define RAYLANE_FOR_EACH_WIDTH(X) X(8) X(16)
#elif defined(__AVX2__) && defined(__FMA__)
#define RAYLANE_FOR_EACH_WIDTH(X) X(8)
#else
#define RAYLANE_FOR_EACH_WIDTH(X) X(1) X(4)
#endif

namespace simd_detail {
// The xsimd architecture behind each width; void where this instruction set cannot run it. The FMA
// variants matter only for xsimd's own kernels: fma() in math.h emits FMA instructions itself.
#if XSIMD_WITH_AVX512BW
using Arch16 = xsimd::avx512bw;
#elif XSIMD_WITH_AVX512F
using Arch16 = xsimd::avx512f;
#else
using Arch16 = void;
#endif
#if XSIMD_WITH_FMA3_AVX2
using Arch8 = xsimd::fma3<xsimd::avx2>;
#elif XSIMD_WITH_AVX2
using Arch8 = xsimd::avx2;
#else
using Arch8 = void;
#endif
#if XSIMD_WITH_FMA3_SSE
using Arch4 = xsimd::fma3<xsimd::sse4_2>;
#elif XSIMD_WITH_SSE4_2
using Arch4 = xsimd::sse4_2;
#elif XSIMD_WITH_SSE2
using Arch4 = xsimd::sse2;
#else
using Arch4 = void;
#endif
template <int W>
using ArchFor =
    std::conditional_t<W == 16, Arch16,
                       std::conditional_t<W == 8, Arch8, std::conditional_t<W == 4, Arch4, void>>>;

template <int W>
struct Packet {
    using Arch = ArchFor<W>;
    using Float = xsimd::batch<float, Arch>;
    using Int = xsimd::batch<int32_t, Arch>;
    using Mask = xsimd::batch_bool<float, Arch>;
};
template <>
struct Packet<1> {
    using Float = float;
    using Int = int32_t;
    using Mask = bool;
};
}  // namespace simd_detail

/// True when this instruction set can run packets of width W (1 always; 4, 8, 16 as it allows).
template <int W>
inline constexpr bool width_supported = W == 1 || !std::is_void_v<simd_detail::ArchFor<W>>;
static_assert(width_supported<native_width>);

/// W floats, W int32 lanes, and a W-lane mask usable with vfloat<W>. At W == 1: float, int32_t,
/// bool. These are aliases, so W cannot be deduced from them: kernels receive W explicitly.
template <int W>
using vfloat = typename simd_detail::Packet<W>::Float;
template <int W>
using vint = typename simd_detail::Packet<W>::Int;
template <int W>
using vmask = typename simd_detail::Packet<W>::Mask;

/// Packet types spelled by architecture. The W > 1 overloads in simd/ take these and deduce A, so
/// they are more specialised than xsimd's batch<T, A> templates and win when argument-dependent
/// lookup finds both (xsimd::store, for one, is an aligned store).
template <class A>
using PFloat = xsimd::batch<float, A>;
template <class A>
using PInt = xsimd::batch<int32_t, A>;
template <class A>
using PMask = xsimd::batch_bool<float, A>;

/// Lane count of a packet type (1 for float, int32_t and bool).
template <class V>
inline constexpr int width_of = 1;
template <class T, class A>
inline constexpr int width_of<xsimd::batch<T, A>> = static_cast<int>(xsimd::batch<T, A>::size);
template <class T, class A>
inline constexpr int width_of<xsimd::batch_bool<T, A>> =
    static_cast<int>(xsimd::batch_bool<T, A>::size);

/// vfloat<W>, vint<W> or vmask<W> for some W (W = 1 included), for width-generic helpers.
template <class V>
concept AnyFloat = std::is_same_v<V, vfloat<width_of<V>>>;
template <class V>
concept AnyInt = std::is_same_v<V, vint<width_of<V>>>;
template <class M>
concept AnyMask = std::is_same_v<M, vmask<width_of<M>>>;

/// A width as a type, for typed tests and benchmarks.
template <int W>
using Width = std::integral_constant<int, W>;

// ---- construction and memory ------------------------------------------------------------------

/// Every lane set to v. The uint32_t overload keeps the bit pattern (hash constants).
template <int W>
inline vfloat<W> broadcast(float v) {
    return vfloat<W>(v);
}
template <int W>
inline vint<W> broadcast(int32_t v) {
    return vint<W>(v);
}
template <int W>
inline vint<W> broadcast(uint32_t v) {
    return vint<W>(static_cast<int32_t>(v));
}

namespace simd_detail {
template <int W, class T>
using PacketOf = std::conditional_t<std::is_same_v<T, float>, vfloat<W>, vint<W>>;
template <class T>
concept Lane = std::is_same_v<T, float> || std::is_same_v<T, int32_t>;
}  // namespace simd_detail

/// Loads W consecutive floats or int32s; load_aligned needs p aligned to 4 W bytes.
template <int W, simd_detail::Lane T>
inline simd_detail::PacketOf<W, T> load(const T* p) {
    if constexpr (W == 1)
        return *p;
    else
        return simd_detail::PacketOf<W, T>::load_unaligned(p);
}
template <int W, simd_detail::Lane T>
inline simd_detail::PacketOf<W, T> load_aligned(const T* p) {
    if constexpr (W == 1)
        return *p;
    else
        return simd_detail::PacketOf<W, T>::load_aligned(p);
}

/// Stores all W lanes of v (masked stores are in lanes.h); store_aligned needs 4 W-byte alignment.
inline void store(float* p, float v) { *p = v; }
inline void store(int32_t* p, int32_t v) { *p = v; }
inline void store_aligned(float* p, float v) { *p = v; }
inline void store_aligned(int32_t* p, int32_t v) { *p = v; }
template <class A>
inline void store(float* p, const PFloat<A>& v) {
    v.store_unaligned(p);
}
template <class A>
inline void store(int32_t* p, const PInt<A>& v) {
    v.store_unaligned(p);
}
template <class A>
inline void store_aligned(float* p, const PFloat<A>& v) {
    v.store_aligned(p);
}
template <class A>
inline void store_aligned(int32_t* p, const PInt<A>& v) {
    v.store_aligned(p);
}

// ---- masks and selection --------------------------------------------------------------------

/// Lane-wise m ? a : b. Returns the operands' bits unchanged (NaN payloads, -0.0 included).
inline float select(bool m, float a, float b) { return m ? a : b; }
inline int32_t select(bool m, int32_t a, int32_t b) { return m ? a : b; }
template <class A>
inline PFloat<A> select(const PMask<A>& m, const PFloat<A>& a, const PFloat<A>& b) {
    return xsimd::select(m, a, b);
}
template <class A>
inline PInt<A> select(const PMask<A>& m, const PInt<A>& a, const PInt<A>& b) {
    return xsimd::select(xsimd::bool_cast(m), a, b);
}

/// Mask logic, andnot(a, b) being "a and not b". Use these, not &, |, !, so code builds at W = 1.
inline bool mask_and(bool a, bool b) { return a && b; }
inline bool mask_or(bool a, bool b) { return a || b; }
inline bool mask_andnot(bool a, bool b) { return a && !b; }
inline bool mask_not(bool a) { return !a; }
template <class A>
inline PMask<A> mask_and(const PMask<A>& a, const PMask<A>& b) {
    return a & b;
}
template <class A>
inline PMask<A> mask_or(const PMask<A>& a, const PMask<A>& b) {
    return a | b;
}
template <class A>
inline PMask<A> mask_andnot(const PMask<A>& a, const PMask<A>& b) {
    return a & ~b;
}
template <class A>
inline PMask<A> mask_not(const PMask<A>& a) {
    return ~a;
}

// ---- operators ------------------------------------------------------------------------------
// Binary +, -, *, / and the comparisons <, <=, >, >=, == on vfloat are the built-in operators at
// every W: IEEE, correctly rounded (division is exact); comparisons give vmask<W>, false for NaN.
// Two xsimd 8.1 operators disagree with float, so never use them on vfloat: `a != b` is false for
// NaN at W = 8 and 16 (use ne), and unary `-v` is 0 - v at W = 16, so +0 stays +0 (use neg).
// min, max, abs, sqrt, neg, ne, is_nan and fma are in math.h.

// ---- int32 lanes ----------------------------------------------------------------------------
// ^, &, | are the built-in operators at every W; add, mul_lo and shifts are in math.h.

/// Signed comparisons of int lanes, as float-compatible masks.
inline bool eq(int32_t a, int32_t b) { return a == b; }
inline bool lt(int32_t a, int32_t b) { return a < b; }
inline bool gt(int32_t a, int32_t b) { return a > b; }
template <class A>
inline PMask<A> eq(const PInt<A>& a, const PInt<A>& b) {
    return xsimd::bool_cast(a == b);
}
template <class A>
inline PMask<A> lt(const PInt<A>& a, const PInt<A>& b) {
    return xsimd::bool_cast(a < b);
}
template <class A>
inline PMask<A> gt(const PInt<A>& a, const PInt<A>& b) {
    return xsimd::bool_cast(a > b);
}

/// Unsigned comparisons of int lanes read as uint32 (keys, ids), as float-compatible masks:
/// a < b and a <= b. AVX-512 compares unsigned lanes itself; elsewhere the sign bits are flipped
/// and the lanes compared signed.
inline bool lt_u32(int32_t a, int32_t b) {
    return static_cast<uint32_t>(a) < static_cast<uint32_t>(b);
}
inline bool le_u32(int32_t a, int32_t b) {
    return static_cast<uint32_t>(a) <= static_cast<uint32_t>(b);
}
template <class A>
inline PMask<A> lt_u32(const PInt<A>& a, const PInt<A>& b) {
#if defined(__AVX512F__)
    if constexpr (width_of<PInt<A>> == 16) return PMask<A>(_mm512_cmplt_epu32_mask(a, b));
#endif
    const PInt<A> sign(std::numeric_limits<int32_t>::min());
    return lt(a ^ sign, b ^ sign);
}
template <class A>
inline PMask<A> le_u32(const PInt<A>& a, const PInt<A>& b) {
#if defined(__AVX512F__)
    if constexpr (width_of<PInt<A>> == 16) return PMask<A>(_mm512_cmple_epu32_mask(a, b));
#endif
    return mask_not(lt_u32(b, a));
}

// ---- conversions ----------------------------------------------------------------------------

/// int32 -> float, rounded to nearest; exact for |v| <= 2^24 (so for uint32 counters < 2^24).
inline float to_float(int32_t v) { return static_cast<float>(v); }
template <class A>
inline PFloat<A> to_float(const PInt<A>& v) {
    return xsimd::to_float(v);
}

/// float -> int32 truncated toward zero. Precondition: |v| < 2^31 and not NaN.
inline int32_t to_int(float v) { return static_cast<int32_t>(v); }
template <class A>
inline PInt<A> to_int(const PFloat<A>& v) {
    return xsimd::to_int(v);
}

/// The same 32 bits read as the other type (no conversion).
inline int32_t float_as_int(float v) { return std::bit_cast<int32_t>(v); }
inline float int_as_float(int32_t v) { return std::bit_cast<float>(v); }
template <class A>
inline PInt<A> float_as_int(const PFloat<A>& v) {
    return xsimd::bitwise_cast<PInt<A>>(v);
}
template <class A>
inline PFloat<A> int_as_float(const PInt<A>& v) {
    return xsimd::bitwise_cast<PFloat<A>>(v);
}

}  // namespace raylane::RAYLANE_ISA_NS
