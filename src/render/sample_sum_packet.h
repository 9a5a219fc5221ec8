// render: sample classification and compensated pixel sums for W pixels, the packet path.
// Mirrors sample_sum_scalar.h operation for operation: every lane gets the scalar's bits.
#pragma once

#include "render/sample_sum_scalar.h"
#include "simd/math.h"
#include "simd/simd.h"
#include "simd/vec3.h"

namespace raylane::RAYLANE_ISA_NS {

template <int W>
inline vmask<W> nonfinite_bits(const vfloat<W>& v) {
    const vint<W> exponent(0x7f800000);
    return eq(float_as_int(v) & exponent, exponent);
}
template <int W>
inline vmask<W> nan_bits(const vfloat<W>& v) {
    return gt(float_as_int(v) & vint<W>(0x7fffffff), vint<W>(0x7f800000));
}

/// Lanes whose sample is NaN (any channel) and lanes whose sample is infinite (no NaN).
template <int W>
inline void sample_kinds(const Vec3<W>& c, vmask<W>& nan, vmask<W>& inf) {
    nan = mask_or(mask_or(nan_bits<W>(c.x), nan_bits<W>(c.y)), nan_bits<W>(c.z));
    const vmask<W> nonfinite =
        mask_or(mask_or(nonfinite_bits<W>(c.x), nonfinite_bits<W>(c.y)), nonfinite_bits<W>(c.z));
    inf = mask_andnot(nonfinite, nan);
}

/// PixelSum of W pixels.
template <int W>
struct PixelSumPacket {
    Vec3<W> sum = make_vec3<W>(0.0f, 0.0f, 0.0f);
    Vec3<W> carry = make_vec3<W>(0.0f, 0.0f, 0.0f);
    vint<W> count = vint<W>(0);
};

/// add_sample in the lanes of `add`; the other lanes keep their sums.
template <int W>
inline void add_sample(PixelSumPacket<W>& p, const Vec3<W>& value, const vmask<W>& add) {
    const Vec3<W> y = value - p.carry;
    const Vec3<W> t = p.sum + y;
    p.carry = select(add, (t - p.sum) - y, p.carry);
    p.sum = select(add, t, p.sum);
    p.count = select(add, raylane::add(p.count, vint<W>(1)), p.count);
}

template <int W>
inline Vec3<W> pixel_mean(const PixelSumPacket<W>& p) {
    const vmask<W> some = gt(p.count, vint<W>(0));
    return select(some, p.sum / select(some, to_float(p.count), vfloat<W>(1.0f)),
                  make_vec3<W>(0.0f, 0.0f, 0.0f));
}

}  // namespace raylane::RAYLANE_ISA_NS
