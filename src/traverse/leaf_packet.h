// traverse: a packet's rays against one leaf of a mesh's wide tree (WideBvh::tris, the leaf's
// triangles in SoA), closest and any hit: the leaf loop of the packet, block and stream
// traversals. Two ways to the same answers, bit for bit the scalar path's:
//  - by triangle: each triangle against the W rays, its coordinates broadcast, for packets with
//    many open lanes;
//  - by ray: each open lane's ray against leaf_lanes triangles at once, one vector load per
//    coordinate and no branch per triangle, for packets with few.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>

#include "accel/bvh.h"
#include "traverse/hit_update_packet.h"
#include "traverse/triangle_packet.h"

namespace raylane::RAYLANE_ISA_NS {

/// Triangles tested at once by one ray: 8 where the build has 8-wide vectors, else 4.
inline constexpr int leaf_lanes = native_width < 8 ? native_width : 8;

/// A leaf's n triangles: their nine coordinate arrays of n floats each from `tris` (a.x, a.y,
/// a.z, b.x, ... c.z), their primitive ids from `ids`. A
/// zero-area triangle's coordinates are NaN (pack_leaf_triangles), so the tests here skip the
/// zero-area test that the scalar path makes: either way the triangle is never hit.
struct LeafTris {
    const float* tris;
    const uint32_t* ids;
    uint32_t n;
};

inline LeafTris leaf_tris(const MeshAccel& mesh, WideRef leaf) {
    return {mesh.wide.tris.data() + 9 * size_t(leaf.child), mesh.bvh.prim_ids.data() + leaf.child,
            leaf.count};
}

/// Vertex `corner` (0, 1, 2: a, b, c) of triangle k, the same for every lane.
inline vec3 leaf_vertex(const LeafTris& leaf, int corner, uint32_t k) {
    const float* p = leaf.tris + 3 * corner * leaf.n + k;
    return vec3(p[0], p[leaf.n], p[2 * leaf.n]);
}

/// Vertex `corner` of triangles k .. k + G - 1, one per lane (lanes past the leaf's end hold
/// other triangles' coordinates or zeros: callers mask them off).
template <int G>
inline Vec3<G> leaf_vertices(const LeafTris& leaf, int corner, uint32_t k) {
    const float* p = leaf.tris + 3 * corner * leaf.n + k;
    return load_vec3<G>(p, p + leaf.n, p + 2 * leaf.n);
}

/// Lane i of `wr` broadcast to G lanes: one ray, prepared for the watertight test exactly as
/// the scalar path prepares it.
template <int G, int W>
inline WatertightPacket<G> lane_watertight(const WatertightPacket<W>& wr, int i) {
    WatertightPacket<G> one;
    one.ox = vfloat<G>(get(wr.ox, i)), one.oy = vfloat<G>(get(wr.oy, i));
    one.oz = vfloat<G>(get(wr.oz, i));
    one.sx = vfloat<G>(get(wr.sx, i)), one.sy = vfloat<G>(get(wr.sy, i));
    one.sz = vfloat<G>(get(wr.sz, i));
    one.org = make_vec3<G>(get(wr.org.x, i), get(wr.org.y, i), get(wr.org.z, i));
    one.dir = make_vec3<G>(get(wr.dir.x, i), get(wr.dir.y, i), get(wr.dir.z, i));
    const uint32_t lane = 1u << i;
    auto axis = [lane](const vmask<W>& k0, const vmask<W>& k1) {
        return (bits(k0) & lane) ? 0 : ((bits(k1) & lane) ? 1 : 2);
    };
    one.kx = axis(wr.kx0, wr.kx1), one.ky = axis(wr.ky0, wr.ky1), one.kz = axis(wr.kz0, wr.kz1);
    one.uniform = true;
    auto on = [](bool b) { return mask_from_bits<G>(b ? ~0u : 0u); };
    one.kx0 = on(one.kx == 0), one.kx1 = on(one.kx == 1);
    one.ky0 = on(one.ky == 0), one.ky1 = on(one.ky == 1);
    one.kz0 = on(one.kz == 0), one.kz1 = on(one.kz == 1);
    return one;
}

/// Whether a packet with `open` lanes tests a leaf of n triangles by ray: a lone open lane in a
/// leaf of two or more. (Allowing more lanes measured no faster on the dragon's shadow and
/// bounce rays.)
inline bool leaf_by_ray(int open, uint32_t n) { return open == 1 && n > 1; }

/// The lanes of `m` one by one against the leaf's triangles, leaf_lanes at a time (leaf_closest
/// for packets with few open lanes).
template <int W>
vmask<W> leaf_closest_by_ray(const LeafTris& leaf, uint32_t object, const WatertightPacket<W>& wr,
                             const RayPacket<W>& rays, vmask<W> m, vfloat<W>& limit,
                             HitPacket<W>& hit) {
    constexpr int G = leaf_lanes;
    uint32_t won = 0;
    for (uint32_t b = bits(m); b != 0; b &= b - 1) {
        const int i = std::countr_zero(b);
        const WatertightPacket<G> one = lane_watertight<G>(wr, i);
        const vfloat<G> t_min(get(rays.t_min, i)), t_max(get(limit, i));
        for (uint32_t k = 0; k < leaf.n; k += G) {
            vfloat<G> t(infinity), u(0.0f), v(0.0f);
            const vmask<G> in_leaf =
                prefix_mask<G>(static_cast<int>(std::min<uint32_t>(G, leaf.n - k)));
            const vmask<G> h = intersect_triangle(
                one, leaf_vertices<G>(leaf, 0, k), leaf_vertices<G>(leaf, 1, k),
                leaf_vertices<G>(leaf, 2, k), t_min, t_max, t, u, v, in_leaf, false);
            if (none(h)) continue;
            // the group's best by (t, primitive), then against the lane's hit
            const float t_best = hmin(t, h);
            int best = -1;
            for (uint32_t tie = bits(mask_and(h, t == vfloat<G>(t_best))); tie != 0;
                 tie &= tie - 1) {
                const int j = std::countr_zero(tie);
                if (best < 0 || leaf.ids[k + j] < leaf.ids[k + best]) best = j;
            }
            const uint32_t prim = leaf.ids[k + best];
            const float t_hit = get(hit.t, i);
            const auto hit_object = static_cast<uint32_t>(get(hit.object, i));
            const auto hit_prim = static_cast<uint32_t>(get(hit.prim, i));
            const bool wins = t_best < t_hit ||
                              (t_best == t_hit &&
                               (object < hit_object || (object == hit_object && prim < hit_prim)));
            if (!wins) continue;
            set(hit.t, i, t_best);
            set(hit.u, i, get(u, best));
            set(hit.v, i, get(v, best));
            set(hit.object, i, static_cast<int32_t>(object));
            set(hit.prim, i, static_cast<int32_t>(prim));
            won |= 1u << i;
        }
    }
    if (won != 0) limit = t_limit(rays, hit);
    return mask_from_bits<W>(won);
}

/// The closest hits of the lanes `m` in the leaf: lanes whose hit beats `hit` (by t, object,
/// primitive) get it, and `limit` follows (t_limit). Returns the lanes that got a hit.
template <int W>
[[gnu::always_inline]] inline vmask<W> leaf_closest(const LeafTris& leaf, uint32_t object,
                                                    const WatertightPacket<W>& wr,
                                                    const RayPacket<W>& rays, vmask<W> m,
                                                    vfloat<W>& limit, HitPacket<W>& hit) {
    if (leaf_by_ray(count(m), leaf.n))
        return leaf_closest_by_ray(leaf, object, wr, rays, m, limit, hit);
    vmask<W> won = mask_and(m, mask_not(m));
    for (uint32_t k = 0; k < leaf.n; ++k) {
        vfloat<W> t(infinity), u(0.0f), v(0.0f);
        const vmask<W> h =
            intersect_triangle(wr, leaf_vertex(leaf, 0, k), leaf_vertex(leaf, 1, k),
                               leaf_vertex(leaf, 2, k), rays.t_min, limit, t, u, v, m, false);
        if (any(h)) {
            const vmask<W> win = better(t, object, leaf.ids[k], hit, h);
            record(hit, win, t, object, leaf.ids[k], u, v);
            limit = t_limit(rays, hit);
            won = mask_or(won, win);
        }
    }
    return won;
}

/// The lanes of `m` one by one against the leaf's triangles (leaf_any for few open lanes).
template <int W>
vmask<W> leaf_any_by_ray(const LeafTris& leaf, const WatertightPacket<W>& wr,
                         const RayPacket<W>& rays, vmask<W> m) {
    constexpr int G = leaf_lanes;
    uint32_t found = 0;
    for (uint32_t b = bits(m); b != 0; b &= b - 1) {
        const int i = std::countr_zero(b);
        const WatertightPacket<G> one = lane_watertight<G>(wr, i);
        const vfloat<G> t_min(get(rays.t_min, i)), t_max(get(rays.t_max, i));
        for (uint32_t k = 0; k < leaf.n; k += G) {
            vfloat<G> t(infinity), u(0.0f), v(0.0f);
            const vmask<G> in_leaf =
                prefix_mask<G>(static_cast<int>(std::min<uint32_t>(G, leaf.n - k)));
            if (any(intersect_triangle(one, leaf_vertices<G>(leaf, 0, k),
                                       leaf_vertices<G>(leaf, 1, k), leaf_vertices<G>(leaf, 2, k),
                                       t_min, t_max, t, u, v, in_leaf, false))) {
                found |= 1u << i;
                break;
            }
        }
    }
    return mask_from_bits<W>(found);
}

/// The lanes of `m` that some triangle of the leaf occludes (hits within (t_min, t_max)).
template <int W>
[[gnu::always_inline]] inline vmask<W> leaf_any(const LeafTris& leaf, const WatertightPacket<W>& wr,
                                                const RayPacket<W>& rays, vmask<W> m) {
    if (leaf_by_ray(count(m), leaf.n)) return leaf_any_by_ray(leaf, wr, rays, m);
    vmask<W> found = mask_and(m, mask_not(m));
    for (uint32_t k = 0; k < leaf.n; ++k) {
        const vmask<W> lanes = mask_andnot(m, found);
        if (none(lanes)) break;
        vfloat<W> t(infinity), u(0.0f), v(0.0f);
        found = mask_or(found, intersect_triangle(wr, leaf_vertex(leaf, 0, k),
                                                  leaf_vertex(leaf, 1, k), leaf_vertex(leaf, 2, k),
                                                  rays.t_min, rays.t_max, t, u, v, lanes, false));
    }
    return found;
}

}  // namespace raylane::RAYLANE_ISA_NS
