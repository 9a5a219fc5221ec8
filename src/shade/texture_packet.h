// shade: texture lookup, environment mapping and normal maps for W lanes, the packet path.
// Mirrors texture_scalar.h operation by operation: every lane is bit-identical to the scalar.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "scene/scene.h"
#include "shade/texture_scalar.h"
#include "simd/lanes.h"
#include "simd/math.h"
#include "simd/vec3.h"

namespace raylane::RAYLANE_ISA_NS {

/// W texture coordinates.
template <int W>
struct Uv {
    vfloat<W> u = vfloat<W>(0.0f);
    vfloat<W> v = vfloat<W>(0.0f);
};

// texture_detail (texture_scalar.h) holds the constants both twins share
namespace texture_packet_detail {

// floor, round (half away from zero), atan2, asin lane by lane: floor and round are exact in
// xsimd, so they agree at every W; atan2 and asin call std:: per lane, because a texel chosen by
// nearest look-up flips on a one-ulp difference and the two paths must see the same texel.
inline float floor_lanes(float v) { return std::floor(v); }
inline float round_lanes(float v) { return std::round(v); }
inline float atan2_lanes(float y, float x) { return std::atan2(y, x); }
inline float asin_lanes(float v) { return std::asin(v); }
template <class A>
inline PFloat<A> floor_lanes(const PFloat<A>& v) {
    return xsimd::floor(v);
}
template <class A>
inline PFloat<A> round_lanes(const PFloat<A>& v) {
    return xsimd::round(v);
}
template <class A>
inline PFloat<A> atan2_lanes(const PFloat<A>& y, const PFloat<A>& x) {
    constexpr size_t n = PFloat<A>::size;
    alignas(64) float ys[n], xs[n];
    y.store_aligned(ys), x.store_aligned(xs);
    for (size_t i = 0; i < n; ++i) ys[i] = std::atan2(ys[i], xs[i]);
    return PFloat<A>::load_aligned(ys);
}
template <class A>
inline PFloat<A> asin_lanes(const PFloat<A>& v) {
    constexpr size_t n = PFloat<A>::size;
    alignas(64) float vs[n];
    v.store_aligned(vs);
    for (size_t i = 0; i < n; ++i) vs[i] = std::asin(vs[i]);
    return PFloat<A>::load_aligned(vs);
}

/// wrap_coordinate of texture_scalar.cpp: repeat outside [0, 1], then clamp to [0, 1], NaN -> 0.
template <int W>
inline vfloat<W> wrap_coordinate(vfloat<W> c, bool repeat) {
    const vfloat<W> zero(0.0f), one(1.0f);
    if (repeat) c = select(mask_and(c >= zero, c <= one), c, c - floor_lanes(c));
    c = select(c >= zero, c, zero);
    return select(c > one, one, c);
}

/// Texels (x, y) of the lanes in m (indices in range in every lane); 0 in the others.
template <int W>
inline Vec3<W> fetch(const Texture& t, vint<W> x, vint<W> y, vmask<W> m) {
    const vint<W> i = mul_lo(add(mul_lo(y, vint<W>(t.width)), x), vint<W>(3));
    const float* base = t.texels.data();
    return {gather(base, i, m), gather(base + 1, i, m), gather(base + 2, i, m)};
}

template <int W>
inline Vec3<W> image_lookup(const Texture& t, vfloat<W> u, vfloat<W> v, vmask<W> m, bool repeat_u,
                            bool repeat_v) {
    u = wrap_coordinate<W>(u, repeat_u);
    v = wrap_coordinate<W>(v, repeat_v);
    const vfloat<W> width(static_cast<float>(t.width));
    const vfloat<W> height(static_cast<float>(t.height));
    const vfloat<W> one(1.0f);
    if (t.filter == TextureFilter::nearest) {
        const vint<W> x = to_int(round_lanes(u * (width - one)));
        const vint<W> y = to_int(round_lanes((one - v) * (height - one)));
        return fetch<W>(t, x, y, m);
    }
    const vfloat<W> half(0.5f);
    const vfloat<W> x = u * width - half;
    const vfloat<W> y = (one - v) * height - half;
    const vfloat<W> x_floor = floor_lanes(x);
    const vfloat<W> y_floor = floor_lanes(y);
    const vfloat<W> fx = x - x_floor;
    const vfloat<W> fy = y - y_floor;
    const vint<W> zero(0), last_x(t.width - 1), last_y(t.height - 1);
    vint<W> x0 = to_int(x_floor), x1 = add(x0, vint<W>(1));
    vint<W> y0 = to_int(y_floor), y1 = add(y0, vint<W>(1));
    if (repeat_u) {
        x0 = select(lt(x0, zero), last_x, x0);
        x1 = select(gt(x1, last_x), zero, x1);
    } else {
        x0 = select(lt(x0, zero), zero, x0);
        x1 = select(gt(x1, last_x), last_x, x1);
    }
    if (repeat_v) {
        y0 = select(lt(y0, zero), last_y, y0);
        y1 = select(gt(y1, last_y), zero, y1);
    } else {
        y0 = select(lt(y0, zero), zero, y0);
        y1 = select(gt(y1, last_y), last_y, y1);
    }
    const Vec3<W> c00 = fetch<W>(t, x0, y0, m), c10 = fetch<W>(t, x1, y0, m);
    const Vec3<W> c01 = fetch<W>(t, x0, y1, m), c11 = fetch<W>(t, x1, y1, m);
    const vfloat<W> gx = one - fx, gy = one - fy;
    return {(c00.x * gx + c10.x * fx) * gy + (c01.x * gx + c11.x * fx) * fy,
            (c00.y * gx + c10.y * fx) * gy + (c01.y * gx + c11.y * fx) * fy,
            (c00.z * gx + c10.z * fx) * gy + (c01.z * gx + c11.z * fx) * fy};
}

template <int W>
inline Vec3<W> checker_lookup(const Texture& t, vfloat<W> u, vfloat<W> v, vmask<W> m) {
    const vfloat<W> checks(t.checks);
    const vfloat<W> s = floor_lanes(u * checks) + floor_lanes(v * checks);
    const vmask<W> even = s - floor_lanes(s * vfloat<W>(0.5f)) * vfloat<W>(2.0f) == vfloat<W>(0.0f);
    const Vec3<W> a = make_vec3<W>(t.color_a.x, t.color_a.y, t.color_a.z);
    const Vec3<W> b = make_vec3<W>(t.color_b.x, t.color_b.y, t.color_b.z);
    return select(m, select(even, a, b), Vec3<W>{});
}

template <int W>
inline Vec3<W> perpendicular(const Vec3<W>& n) {
    const vfloat<W> sign = copysign(vfloat<W>(1.0f), n.z);
    const vfloat<W> a = vfloat<W>(-1.0f) / (sign + n.z);
    const vfloat<W> b = n.x * n.y * a;
    return {vfloat<W>(1.0f) + sign * n.x * n.x * a, sign * b, neg(sign) * n.x};
}

}  // namespace texture_packet_detail

/// texture_lookup of texture_scalar.h with each axis's wrap mode given, for the lanes in
/// `active`: each active lane equals the scalar result for its (u, v) bit for bit. Inactive
/// lanes are 0 and read no texel. Texel indices are computed in SIMD (always in range, NaN
/// coordinates included) and fetched by masked gathers.
template <int W>
inline Vec3<W> texture_lookup(const Texture& t, vfloat<W> u, vfloat<W> v, vmask<W> active,
                              bool repeat_u, bool repeat_v) {
    using namespace texture_detail;
    using namespace texture_packet_detail;
    const vmask<W> m = mask_andnot(mask_andnot(active, is_nan(u)), is_nan(v));  // NaN: black
    if (none(m)) return {};
    if (t.kind == TextureKind::checker) return checker_lookup<W>(t, u, v, m);
    if (t.width <= 0 || t.height <= 0 ||
        t.texels.size() < static_cast<size_t>(t.width) * static_cast<size_t>(t.height) * 3)
        return {};
    return image_lookup<W>(t, u, v, m, repeat_u, repeat_v);
}

/// texture_lookup of texture_scalar.h for the lanes in `active` (wrap modes from t.repeat).
template <int W>
inline Vec3<W> texture_lookup(const Texture& t, vfloat<W> u, vfloat<W> v, vmask<W> active) {
    return texture_lookup<W>(t, u, v, active, t.repeat, t.repeat);
}

/// latlong_uv of texture_scalar.h for every lane, bit-identical (atan2 and asin are std::'s,
/// lane by lane).
template <int W>
inline Uv<W> latlong_uv(const Vec3<W>& dir) {
    using namespace texture_detail;
    using namespace texture_packet_detail;
    const vfloat<W> one(1.0f), minus_one(-1.0f);
    const vfloat<W> largest = max(max(abs(dir.x), abs(dir.y)), abs(dir.z));
    const Vec3<W> d{dir.x / largest, dir.y / largest, dir.z / largest};
    vfloat<W> s = d.y / sqrt(dot(d, d));
    s = select(s > one, one, s);
    s = select(s < minus_one, minus_one, s);
    const vfloat<W> zero(0.0f);
    const vfloat<W> x = select(mask_and(dir.x == zero, dir.z == zero), one, dir.x);
    vfloat<W> u = (atan2_lanes(dir.z, x) + vfloat<W>(pi)) / vfloat<W>(two_pi);
    vfloat<W> v = asin_lanes(s) / vfloat<W>(pi) + vfloat<W>(0.5f);
    u = select(u > one, one, u);
    u = select(u < zero, zero, u);
    v = select(v > one, one, v);
    v = select(v < zero, zero, v);
    u = select(is_nan(v), v, u);
    return {u, v};
}

/// environment_lookup of texture_scalar.h for the lanes in `active` (u repeats, v clamps).
template <int W>
inline Vec3<W> environment_lookup(const Texture& t, const Vec3<W>& dir, vmask<W> active) {
    const Uv<W> uv = latlong_uv<W>(dir);
    return texture_lookup<W>(t, uv.u, uv.v, active, true, false);
}

/// normal_from_map of texture_scalar.h for every lane (one mode and one matrix for the packet;
/// lanes of other materials or meshes are the caller's to mask). Bit-identical to the scalar.
template <int W>
inline Vec3<W> normal_from_map(NormalMapMode mode, const Vec3<W>& texel, const Vec3<W>& n,
                               const Vec3<W>& dpdu, const glm::mat3& normal_to_world) {
    using namespace texture_detail;
    using namespace texture_packet_detail;
    const Vec3<W> nn = normalize(n);
    Vec3<W> m;
    if (mode == NormalMapMode::replace) {
        const Vec3<W> c = texel - make_vec3<W>(0.5f, 0.5f, 0.5f);
        const glm::mat3& a = normal_to_world;
        auto row = [&](int i) {
            return vfloat<W>(a[0][i]) * c.x + vfloat<W>(a[1][i]) * c.y + vfloat<W>(a[2][i]) * c.z;
        };
        m = {row(0), row(1), row(2)};
    } else {
        Vec3<W> t = dpdu - nn * dot(nn, dpdu);
        const vfloat<W> t2 = dot(t, t);
        const vmask<W> usable = t2 > vfloat<W>(tangent_parallel_fraction) * dot(dpdu, dpdu);
        t = select(usable, t * (vfloat<W>(1.0f) / sqrt(t2)), perpendicular(nn));
        const Vec3<W> b = cross(nn, t);
        const Vec3<W> d = texel * vfloat<W>(2.0f) - make_vec3<W>(1.0f, 1.0f, 1.0f);
        m = (t * d.x + b * d.y) + nn * d.z;
    }
    const vfloat<W> m2 = dot(m, m);
    return select(m2 >= vfloat<W>(min_normal_length2), m * (vfloat<W>(1.0f) / sqrt(m2)), nn);
}

/// keep_above of texture_scalar.h for every lane (the bend is a per-lane select).
template <int W>
inline Vec3<W> keep_above(const Vec3<W>& ns, const Vec3<W>& r) {
    using namespace texture_detail;
    using namespace texture_packet_detail;
    const vfloat<W> c = dot(ns, r);
    const vfloat<W> cos_min(keep_above_cos);
    const vmask<W> above = c >= cos_min;
    if (all(above)) return ns;  // the common case: no lane to bend
    const Vec3<W> t = ns - r * c;
    const vfloat<W> t_length = sqrt(dot(t, t));
    const vfloat<W> s(std::sqrt(1.0f - keep_above_cos * keep_above_cos));
    const Vec3<W> bent = t * (s / t_length) + r * cos_min;
    return select(above, ns, select(t_length > vfloat<W>(1e-6f), bent, r));
}

/// face_viewer of texture_scalar.h for every lane.
template <int W>
inline Vec3<W> face_viewer(const Vec3<W>& ns, const Vec3<W>& ng, const Vec3<W>& wo) {
    using namespace texture_detail;
    using namespace texture_packet_detail;
    const vfloat<W> cos_min(keep_above_cos);
    const vfloat<W> a = dot(ns, wo);
    const vmask<W> facing = a >= cos_min;
    if (all(facing)) return ns;
    const vfloat<W> b = dot(ng, wo);
    const vfloat<W> lambda = select(b > cos_min, (cos_min - a) / (b - a), vfloat<W>(1.0f));
    const Vec3<W> m = ns + (ng - ns) * lambda;
    return select(facing, ns, m / sqrt(dot(m, m)));
}

}  // namespace raylane::RAYLANE_ISA_NS
