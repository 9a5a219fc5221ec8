// traverse: watertight ray/triangle intersection, W rays against one triangle or one ray against
// W triangles (the packet path). Mirrors triangle_scalar.h step by step; the float expressions are
// the same, so a lane's result is bit-identical to the scalar test of the same ray.
// Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013.
#pragma once

#include <type_traits>

#include "core/ray_packet.h"
#include "traverse/triangle_scalar.h"

namespace raylane::RAYLANE_ISA_NS {

/// W rays prepared for the watertight test. The axis permutation (kx, ky, kz) is per lane;
/// when all lanes share it (coherent rays) `uniform` is set and kx, ky, kz hold it, so the
/// triangle's vertices are permuted once instead of per lane. The origin is stored permuted.
template <int W>
struct WatertightPacket {
    vfloat<W> ox, oy, oz;  ///< org[kx], org[ky], org[kz]
    vfloat<W> sx, sy, sz;
    Vec3<W> org, dir;  ///< the rays' own origins and directions (plane_distance_in_double)
    vmask<W> kx0, kx1, ky0, ky1, kz0, kz1;  ///< lane masks: kx == 0, kx == 1, ...
    bool uniform = true;
    int kx = 0, ky = 1, kz = 2;
};

/// Lane-wise m ? a : b for masks.
template <class M>
inline M select_mask(const M& m, const M& a, const M& b) {
    return mask_or(mask_and(m, a), mask_andnot(b, m));
}

/// Component k of each lane's vector, k given by the masks (k == 0, k == 1, else 2).
template <int W>
inline vfloat<W> pick(const vmask<W>& k0, const vmask<W>& k1, const Vec3<W>& p) {
    return select(k0, p.x, select(k1, p.y, p.z));
}
template <int W>
inline vfloat<W> pick(const vmask<W>& k0, const vmask<W>& k1, vec3 p) {
    return select(k0, vfloat<W>(p.x), select(k1, vfloat<W>(p.y), vfloat<W>(p.z)));
}

/// Lane-wise make_watertight_ray, written into `wr`: the same permutation rule and the same
/// divisions. (Packet only: a block fills an array element in place instead of copying a
/// temporary of 832 bytes; the scalar set-up is a few floats.)
template <int W>
inline void fill_watertight_ray(WatertightPacket<W>& wr, const RayPacket<W>& rays,
                                vmask<W> active) {
    const vfloat<W> adx = abs(rays.dir.x), ady = abs(rays.dir.y), adz = abs(rays.dir.z);
    // kz: x if |x| >= |y| and |x| >= |z|; else y if |y| >= |z|; else z (the scalar rule)
    const vmask<W> x_ge_y = adx >= ady;
    const vmask<W> kz0 = mask_and(x_ge_y, adx >= adz);
    const vmask<W> kz1 = mask_andnot(ady >= adz, x_ge_y);
    const vmask<W> kz2 = mask_not(mask_or(kz0, kz1));
    const vfloat<W> dz = select(kz0, rays.dir.x, select(kz1, rays.dir.y, rays.dir.z));
    const vmask<W> flip = dz < vfloat<W>(0.0f);
    // kx = kz + 1, ky = kz + 2 (mod 3), swapped when dir[kz] < 0
    const vmask<W> cx0 = kz2, cx1 = kz0;  // (kz + 1) % 3 == 0 when kz == 2, == 1 when kz == 0
    const vmask<W> cy0 = kz1, cy1 = kz2;  // (kz + 2) % 3
    wr.kx0 = select_mask<vmask<W>>(flip, cy0, cx0);
    wr.kx1 = select_mask<vmask<W>>(flip, cy1, cx1);
    wr.ky0 = select_mask<vmask<W>>(flip, cx0, cy0);
    wr.ky1 = select_mask<vmask<W>>(flip, cx1, cy1);
    wr.kz0 = kz0;
    wr.kz1 = kz1;
    const vfloat<W> dx = pick<W>(wr.kx0, wr.kx1, rays.dir);
    const vfloat<W> dy = pick<W>(wr.ky0, wr.ky1, rays.dir);
    wr.ox = pick<W>(wr.kx0, wr.kx1, rays.org);
    wr.oy = pick<W>(wr.ky0, wr.ky1, rays.org);
    wr.oz = pick<W>(wr.kz0, wr.kz1, rays.org);
    wr.sx = dx / dz;
    wr.sy = dy / dz;
    wr.sz = vfloat<W>(1.0f) / dz;
    wr.org = rays.org;
    wr.dir = rays.dir;
    // uniform: every active lane has the same (kx, ky, kz)
    const uint32_t act = bits(active);
    const uint32_t bx0 = bits(wr.kx0) & act, bx1 = bits(wr.kx1) & act;
    const uint32_t by0 = bits(wr.ky0) & act, by1 = bits(wr.ky1) & act;
    const uint32_t bz0 = bits(kz0) & act, bz1 = bits(kz1) & act;
    auto same = [act](uint32_t b) { return b == 0 || b == act; };
    wr.uniform = same(bx0) && same(bx1) && same(by0) && same(by1) && same(bz0) && same(bz1);
    wr.kx = 0, wr.ky = 1, wr.kz = 2;
    if (wr.uniform && act != 0) {
        wr.kx = bx0 ? 0 : (bx1 ? 1 : 2);
        wr.ky = by0 ? 0 : (by1 ? 1 : 2);
        wr.kz = bz0 ? 0 : (bz1 ? 1 : 2);
    }
}
template <int W>
inline WatertightPacket<W> make_watertight_ray(const RayPacket<W>& rays, vmask<W> active) {
    WatertightPacket<W> wr;
    fill_watertight_ray(wr, rays, active);
    return wr;
}

/// Component k (0, 1 or 2) of a vertex: one triangle's for every lane (vec3), or each lane's
/// own triangle (Vec3<W>).
inline float component(vec3 p, int k) { return p[k]; }
template <int W>
inline vfloat<W> component(const Vec3<W>& p, int k) {
    return k == 0 ? p.x : (k == 1 ? p.y : p.z);
}

/// Lane i's vertex.
inline vec3 lane_vertex(vec3 p, int) { return p; }
template <int W>
inline vec3 lane_vertex(const Vec3<W>& p, int i) {
    return get_vec3(p, i);
}

/// The lanes of `active` that hit triangle (a, b, c) at t in (t_min, t_max); for those lanes t,
/// u, v are written (others keep their values). Same steps as the scalar test. The vertices
/// are one triangle's for all lanes (V = vec3: W rays against a triangle) or a triangle per lane
/// (V = Vec3<W>: one ray, broadcast into wr, against W triangles of a leaf). With `test_area`
/// false, and always for a triangle per lane, the caller guarantees that no triangle has zero
/// area or that such a triangle's vertices are NaN (a wide leaf's: WideBvh::tris), which no ray
/// hits either.
template <int W, class V>
[[gnu::always_inline]] inline vmask<W> intersect_triangle(const WatertightPacket<W>& wr, const V& a,
                                                          const V& b, const V& c,
                                                          const vfloat<W>& t_min,
                                                          const vfloat<W>& t_max, vfloat<W>& t,
                                                          vfloat<W>& u, vfloat<W>& v,
                                                          vmask<W> active, bool test_area = true) {
    // translate (vertex components picked by the permutation, then the permuted origin)
    vfloat<W> akx, aky, akz, bkx, bky, bkz, ckx, cky, ckz;
    if (wr.uniform) {
        akx = vfloat<W>(component(a, wr.kx)), aky = vfloat<W>(component(a, wr.ky)),
        akz = vfloat<W>(component(a, wr.kz));
        bkx = vfloat<W>(component(b, wr.kx)), bky = vfloat<W>(component(b, wr.ky)),
        bkz = vfloat<W>(component(b, wr.kz));
        ckx = vfloat<W>(component(c, wr.kx)), cky = vfloat<W>(component(c, wr.ky)),
        ckz = vfloat<W>(component(c, wr.kz));
    } else {
        akx = pick<W>(wr.kx0, wr.kx1, a), aky = pick<W>(wr.ky0, wr.ky1, a),
        akz = pick<W>(wr.kz0, wr.kz1, a);
        bkx = pick<W>(wr.kx0, wr.kx1, b), bky = pick<W>(wr.ky0, wr.ky1, b),
        bkz = pick<W>(wr.kz0, wr.kz1, b);
        ckx = pick<W>(wr.kx0, wr.kx1, c), cky = pick<W>(wr.ky0, wr.ky1, c),
        ckz = pick<W>(wr.kz0, wr.kz1, c);
    }
    const vfloat<W> Akz = akz - wr.oz, Bkz = bkz - wr.oz, Ckz = ckz - wr.oz;

    // shear
    const vfloat<W> ax = (akx - wr.ox) - wr.sx * Akz;
    const vfloat<W> ay = (aky - wr.oy) - wr.sy * Akz;
    const vfloat<W> bx = (bkx - wr.ox) - wr.sx * Bkz;
    const vfloat<W> by = (bky - wr.oy) - wr.sy * Bkz;
    const vfloat<W> cx = (ckx - wr.ox) - wr.sx * Ckz;
    const vfloat<W> cy = (cky - wr.oy) - wr.sy * Ckz;

    // edge functions
    vfloat<W> e_a = cx * by - cy * bx;
    vfloat<W> e_b = ax * cy - ay * cx;
    vfloat<W> e_c = bx * ay - by * ax;

    // fallback: lanes with an exactly zero edge function recompute all three in double
    const vfloat<W> zero(0.0f);
    const vmask<W> any_zero =
        mask_and(mask_or(mask_or(e_a == zero, e_b == zero), e_c == zero), active);
    if (any(any_zero)) {
        for_each_active(any_zero, [&](int i) {
            const double dax = get(ax, i), day = get(ay, i), dbx = get(bx, i);
            const double dby = get(by, i), dcx = get(cx, i), dcy = get(cy, i);
            set(e_a, i, static_cast<float>(dcx * dby - dcy * dbx));
            set(e_b, i, static_cast<float>(dax * dcy - day * dcx));
            set(e_c, i, static_cast<float>(dbx * day - dby * dax));
        });
    }

    // inside
    const vmask<W> inside = mask_or(mask_and(mask_and(e_a >= zero, e_b >= zero), e_c >= zero),
                                    mask_and(mask_and(e_a <= zero, e_b <= zero), e_c <= zero));
    const vfloat<W> det = e_a + e_b + e_c;
    vmask<W> hit = mask_and(mask_and(inside, ne(det, zero)), active);
    if (none(hit)) return hit;

    // degenerate: a property of the triangle alone, tested once for all lanes
    if constexpr (std::is_same_v<V, vec3>) {
        if (test_area && is_zero_area_triangle(a, b, c)) return mask_and(hit, mask_not(hit));
    }

    // distance
    const vfloat<W> az = wr.sz * Akz;
    const vfloat<W> bz = wr.sz * Bkz;
    const vfloat<W> cz = wr.sz * Ckz;
    const vfloat<W> t_scaled = e_a * az + e_b * bz + e_c * cz;
    const vfloat<W> det_sign = select(det < zero, vfloat<W>(-1.0f), vfloat<W>(1.0f));
    const vfloat<W> abs_det = det_sign * det;
    const vfloat<W> t_signed = det_sign * t_scaled;
    // cancellation: unless surely outside the interval, t from the plane in double, lane by lane
    const vfloat<W> terms = abs(e_a * az) + abs(e_b * bz) + abs(e_c * cz);
    vmask<W> cancel = mask_and(hit, terms > vfloat<W>(2.0f) * abs(t_scaled));
    vfloat<W> t_plane = zero;
    if (any(cancel)) {
        const vfloat<W> slack = terms * vfloat<W>(0x1.0p-10f);
        const vmask<W> outside =
            mask_or(t_signed + slack<t_min * abs_det, t_signed - slack> t_max * abs_det);
        hit = mask_andnot(hit, mask_and(cancel, outside));
        cancel = mask_andnot(cancel, outside);
        for_each_active(cancel, [&](int i) {
            set(t_plane, i,
                plane_distance_in_double(vec3(get(wr.org.x, i), get(wr.org.y, i), get(wr.org.z, i)),
                                         vec3(get(wr.dir.x, i), get(wr.dir.y, i), get(wr.dir.z, i)),
                                         lane_vertex(a, i), lane_vertex(b, i), lane_vertex(c, i)));
        });
    }
    const vmask<W> in_scaled = mask_and(t_signed > t_min * abs_det, t_signed < t_max * abs_det);
    hit = mask_or(cancel, mask_and(mask_andnot(hit, cancel), in_scaled));
    if (none(hit)) return hit;

    // divide
    const vfloat<W> t_hit = select(cancel, t_plane, t_scaled / det);
    hit = mask_and(hit, mask_and(t_hit > t_min, t_hit < t_max));
    t = select(hit, t_hit, t);
    u = select(hit, e_b / det, u);
    v = select(hit, e_c / det, v);
    return hit;
}

}  // namespace raylane::RAYLANE_ISA_NS
