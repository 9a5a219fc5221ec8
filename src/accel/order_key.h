// accel: the median-split build's sort keys: a float's bits mapped to a uint32 of the same order,
// for one float and for a packet, and the packet width of the build's loops.
#pragma once

#include <bit>
#include <cstdint>

#include "simd/array_packets.h"
#include "simd/math.h"
#include "simd/simd.h"

namespace raylane::RAYLANE_ISA_NS::median_detail {

/// The packet width of the build's vector loops: this instruction set's width (simd/simd.h).
/// Every width gives the same tree.
inline constexpr int build_width = native_width;

/// Whether the build's loops run a packet of build_width primitives at a time: where compaction
/// and the masked loads, stores and gathers are single instructions (simd/lanes.h). Elsewhere the
/// branch-free scalar loops run alone (packet loops made the splits up to 8x slower there).
inline constexpr bool packet_loops = compaction_is_native<build_width>;

/// A float's sign bit, and the top bit of a key.
inline constexpr uint32_t sign_bit = 0x80000000u;

/// A float's bits mapped to an unsigned key with the same order (negatives flipped; -0 sorts
/// before +0).
inline uint32_t order_key(float f) {
    const uint32_t u = std::bit_cast<uint32_t>(f);
    return (u & sign_bit) ? ~u : (u | sign_bit);
}

/// order_key of every lane, as int lanes holding the keys' bits: the bits flipped are every bit
/// of a negative float (its sign spread by the arithmetic shift) and the sign bit of the others.
template <AnyFloat V>
inline vint<width_of<V>> order_keys(const V& f) {
    const vint<width_of<V>> u = float_as_int(f);
    return u ^ (shift_right_arith<31>(u) | broadcast<width_of<V>>(sign_bit));
}

/// The float whose order_key is `key`.
inline float key_value(uint32_t key) {
    return std::bit_cast<float>((key & sign_bit) ? (key & ~sign_bit) : ~key);
}

/// uint32 arrays (ids, keys) as the int32 lanes that simd/ loads and stores: the same bits.
inline int32_t* as_lanes(uint32_t* p) { return reinterpret_cast<int32_t*>(p); }
inline const int32_t* as_lanes(const uint32_t* p) { return reinterpret_cast<const int32_t*>(p); }

}  // namespace raylane::RAYLANE_ISA_NS::median_detail
