// simd: Vec3<W>, three packets (x, y, z) holding W vectors in SoA form; mirrors glm::vec3 on the
// scalar path, with the same operation order so that W = 1 matches glm bit for bit.
#pragma once

#include <cstdint>

#include "simd/math.h"
#include "simd/simd.h"

namespace raylane::RAYLANE_ISA_NS {

/// W three-component vectors, one packet per component.
template <int W>
struct Vec3 {
    vfloat<W> x = vfloat<W>(0.0f);
    vfloat<W> y = vfloat<W>(0.0f);
    vfloat<W> z = vfloat<W>(0.0f);
};

/// Every lane holds (x, y, z).
template <int W>
inline Vec3<W> make_vec3(float x, float y, float z) {
    return {vfloat<W>(x), vfloat<W>(y), vfloat<W>(z)};
}

/// A scalar vector (anything with x, y and z, such as GLM's vec3) in every lane.
template <int W, class V>
inline Vec3<W> broadcast_vec3(const V& v) {
    return make_vec3<W>(v.x, v.y, v.z);
}

/// W consecutive vectors from three SoA arrays; xs, ys, zs point at the first (any alignment).
template <int W>
inline Vec3<W> load_vec3(const float* xs, const float* ys, const float* zs) {
    return {load<W>(xs), load<W>(ys), load<W>(zs)};
}

/// Stores all W lanes into three SoA arrays.
template <int W>
inline void store_vec3(float* xs, float* ys, float* zs, const Vec3<W>& v) {
    store(xs, v.x);
    store(ys, v.y);
    store(zs, v.z);
}

namespace simd_detail {
/// store_vec3_aos at W = 16: for run k of 16 floats, each element's source lane in x (lane) or
/// y (16 + lane) for the x and y components, in z for the z components (zmask).
struct AosRuns {
    alignas(64) int32_t xy[3][16] = {};
    alignas(64) int32_t z[3][16] = {};
    uint16_t zmask[3] = {};
};
constexpr AosRuns make_aos_runs() {
    AosRuns t;
    for (int k = 0; k < 3; ++k) {
        for (int j = 0; j < 16; ++j) {
            const int e = 16 * k + j, lane = e / 3, component = e % 3;
            if (component == 2) {
                t.z[k][j] = lane;
                t.zmask[k] = static_cast<uint16_t>(t.zmask[k] | (1u << j));
            } else {
                t.xy[k][j] = component == 0 ? lane : 16 + lane;
            }
        }
    }
    return t;
}
inline constexpr AosRuns aos_runs = make_aos_runs();
}  // namespace simd_detail

/// Stores the W vectors as consecutive triples x0 y0 z0 x1 y1 z1 ... at out[0 .. 3W) (array of
/// structures: a film's pixels). At W = 16 each run of 16 floats is a two-source permute of x
/// and y and a masked permute of z; other widths go through memory.
template <int W>
inline void store_vec3_aos(float* out, const Vec3<W>& v) {
    if constexpr (W == 1) {
        out[0] = v.x, out[1] = v.y, out[2] = v.z;
        return;
    }
#if defined(__AVX512F__)
    if constexpr (W == 16) {
        const simd_detail::AosRuns& t = simd_detail::aos_runs;
        for (int k = 0; k < 3; ++k) {
            const __m512 xy = _mm512_permutex2var_ps(v.x, _mm512_load_si512(t.xy[k]), v.y);
            _mm512_storeu_ps(out + 16 * k,
                             _mm512_mask_permutexvar_ps(xy, static_cast<__mmask16>(t.zmask[k]),
                                                        _mm512_load_si512(t.z[k]), v.z));
        }
        return;
    }
#endif
    if constexpr (W > 1) {
        alignas(64) float lanes[3][W];
        v.x.store_aligned(lanes[0]), v.y.store_aligned(lanes[1]), v.z.store_aligned(lanes[2]);
        for (int i = 0; i < W; ++i)
            for (int c = 0; c < 3; ++c) out[3 * i + c] = lanes[c][i];
    }
}

// Component-wise arithmetic. A float converts to vfloat<W> where a vfloat<W> is expected.
template <int W>
inline Vec3<W> operator+(const Vec3<W>& a, const Vec3<W>& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <int W>
inline Vec3<W> operator-(const Vec3<W>& a, const Vec3<W>& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <int W>
inline Vec3<W> operator-(const Vec3<W>& a) {
    return {neg(a.x), neg(a.y), neg(a.z)};
}
template <int W>
inline Vec3<W> operator*(const Vec3<W>& a, const Vec3<W>& b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <int W>
inline Vec3<W> operator*(const Vec3<W>& a, const vfloat<W>& s) {
    return {a.x * s, a.y * s, a.z * s};
}
template <int W>
inline Vec3<W> operator*(const vfloat<W>& s, const Vec3<W>& a) {
    return {s * a.x, s * a.y, s * a.z};
}
template <int W>
inline Vec3<W> operator/(const Vec3<W>& a, const vfloat<W>& s) {
    return {a.x / s, a.y / s, a.z / s};
}

/// (a.x b.x + a.y b.y) + a.z b.z, the order glm::dot uses (no FMA).
template <int W>
inline vfloat<W> dot(const Vec3<W>& a, const Vec3<W>& b) {
    return (a.x * b.x + a.y * b.y) + a.z * b.z;
}

/// a x b, written as glm::cross is.
template <int W>
inline Vec3<W> cross(const Vec3<W>& a, const Vec3<W>& b) {
    return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}

/// sqrt(dot(a, a)).
template <int W>
inline vfloat<W> length(const Vec3<W>& a) {
    return sqrt(dot(a, a));
}

/// a * (1 / length(a)), as glm::normalize. A zero vector gives NaN lanes (0 * inf).
template <int W>
inline Vec3<W> normalize(const Vec3<W>& a) {
    return a * (vfloat<W>(1.0f) / sqrt(dot(a, a)));
}

/// Component-wise min and max with the NaN order of min / max in simd.h (b when a or b is NaN).
template <int W>
inline Vec3<W> min(const Vec3<W>& a, const Vec3<W>& b) {
    return {min(a.x, b.x), min(a.y, b.y), min(a.z, b.z)};
}
template <int W>
inline Vec3<W> max(const Vec3<W>& a, const Vec3<W>& b) {
    return {max(a.x, b.x), max(a.y, b.y), max(a.z, b.z)};
}

/// Lane-wise m ? a : b for all three components.
template <int W>
inline Vec3<W> select(const vmask<W>& m, const Vec3<W>& a, const Vec3<W>& b) {
    return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}

}  // namespace raylane::RAYLANE_ISA_NS
