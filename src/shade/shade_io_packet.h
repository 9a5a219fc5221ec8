// shade: what the packet path's shading kernels (shade_packet.h) read and write in place of the
// scalar path's recursion: closest hits in arrays, queue entries gathered into registers
// (ShadeInput), and the two targets shade_hits writes to: the wavefront's queues and slots
// (ShadeTarget), or a camera packet's registers and its shadow rays in place (PacketTarget).
// Also the kernels' lane-wise helpers: gathers, accumulation, child path keys.
#pragma once

#include <cstdint>
#include <vector>

#include "core/ray_packet.h"
#include "shade/path_queue.h"
#include "shade/shade_scalar.h"
#include "simd/hash.h"
#include "simd/lanes.h"
#include "traverse/intersect_block.h"

namespace raylane::RAYLANE_ISA_NS {

/// Closest hits of a PathQueue's rays, one array per field (index = ray).
struct HitArrays {
    std::vector<float> t, u, v;
    std::vector<int32_t> prim, object;
    void resize(size_t n) {
        if (t.size() >= n) return;
        for (auto* a : {&t, &u, &v}) a->resize(n);
        prim.resize(n), object.resize(n);
    }
};

/// What shade_hits writes to: the radiance of each path of the pass (index = its entry in the
/// pass's queue; render/wavefront_packet.h adds them to the wavefront's slots after the pass), the
/// shadow queues (one per light) and the next pass's queues.
struct ShadeTarget {
    float* path_r = nullptr;
    float* path_g = nullptr;
    float* path_b = nullptr;
    ShadowQueue* shadows = nullptr;
    PathQueue* next = nullptr;
    /// Rays that travel inside a refractive medium (refracted in, reflected inside): kept apart
    /// from `next` and traced after it, so that a packet holds rays of one kind (a refracted ray
    /// crosses the mesh, a reflected one leaves it: mixed in a packet, their lanes part at once).
    PathQueue* next_inside = nullptr;
    ShadeCounts* counts = nullptr;
};

/// One light sample's shadow rays of a block of camera packets, kept in their packets (the
/// one-pass kernels): ray, contribution if unoccluded, and the lanes that have one.
template <int W>
struct ShadowBlock {
    RayPacket<W> rays[max_block_rays / W];
    Vec3<W> contribution[max_block_rays / W];
    vmask<W> lanes[max_block_rays / W];
};

/// What shade_hits writes to in the one-pass kernels (no secondary rays): the radiance of camera
/// packet `packet` in registers and its shadow rays in place, one ShadowBlock per light sample
/// (light j's samples from shadow_first[j] on).
template <int W>
struct PacketTarget {
    Vec3<W>* value = nullptr;
    ShadowBlock<W>* shadows = nullptr;
    const int* shadow_first = nullptr;
    int packet = 0;
    ShadeCounts* counts = nullptr;
};

namespace shade_detail {

/// v[idx[i]] for the first k lanes (the others get `fill`); idx has room for W entries.
template <int W>
inline vfloat<W> gather_lanes(const std::vector<float>& v, const vint<W>& idx, vmask<W> m,
                              float fill) {
    return select(m, gather(v.data(), idx, m), vfloat<W>(fill));
}
template <int W>
inline vint<W> gather_lanes(const std::vector<int32_t>& v, const vint<W>& idx, vmask<W> m,
                            int32_t fill) {
    const vfloat<W> bits = gather(reinterpret_cast<const float*>(v.data()), idx, m);
    return select(m, float_as_int(bits), vint<W>(fill));
}

/// Adds value to the lanes' paths (each lane is a path of its own).
template <int W>
inline void accumulate(const ShadeTarget& out, const vint<W>& path, const Vec3<W>& value,
                       vmask<W> m) {
    for_each_active(m, [&](int i) {
        const size_t s = static_cast<size_t>(get(path, i));
        out.path_r[s] += get(value.x, i);
        out.path_g[s] += get(value.y, i);
        out.path_b[s] += get(value.z, i);
    });
}

/// The same for one camera packet's registers: its lanes are distinct pixels.
template <int W>
inline void accumulate(const PacketTarget<W>& out, const vint<W>&, const Vec3<W>& value,
                       vmask<W> m) {
    *out.value = select(m, *out.value + value, *out.value);
}

/// Queues the `lit` lanes' shadow rays towards sample i of light j (contribution added to the
/// lane's path if the segment is free).
template <int W>
inline void add_shadow_rays(const ShadeTarget& out, size_t j, int, const Vec3<W>& origin,
                            const Vec3<W>& dir, const vfloat<W>& distance,
                            const Vec3<W>& contribution, const vint<W>& path, vmask<W> lit) {
    push_packet<W>(out.shadows[j], origin, dir, distance, contribution, path, lit);
}
template <int W>
inline void add_shadow_rays(const PacketTarget<W>& out, size_t j, int i, const Vec3<W>& origin,
                            const Vec3<W>& dir, const vfloat<W>& distance,
                            const Vec3<W>& contribution, const vint<W>&, vmask<W> lit) {
    ShadowBlock<W>& b = out.shadows[out.shadow_first[j] + i];
    const int p = out.packet;
    const RayPacket<W> r{origin, dir, vfloat<W>(0.0f), distance};
    if (none(b.lanes[p])) {  // no lanes yet for this light sample: every lane written
        b.rays[p] = r;
        b.contribution[p] = contribution;
        b.lanes[p] = lit;
        return;
    }
    b.rays[p].org = select(lit, r.org, b.rays[p].org);
    b.rays[p].dir = select(lit, r.dir, b.rays[p].dir);
    b.rays[p].t_max = select(lit, r.t_max, b.rays[p].t_max);
    b.contribution[p] = select(lit, contribution, b.contribution[p]);
    b.lanes[p] = mask_or(b.lanes[p], lit);
}

template <int W>
inline vint<W> child_keys(const vint<W>& key, uint32_t purpose, uint32_t index) {
    const vint<W> salt = hash_u32<W>(broadcast<W>((purpose << 28) ^ index ^ 0x68e31da4u));
    return hash_u32<W>(key ^ salt);
}

}  // namespace shade_detail

/// What shading needs of W rays and their closest hits, in registers (the fields of a PathQueue
/// entry, its hit, and the pixel and sample indices that key its random numbers).
template <int W>
struct ShadeInput {
    RayPacket<W> rays;
    HitPacket<W> hits;
    Vec3<W> weight;
    vint<W> slot;  ///< the wavefront slot (sample of a pixel) each lane's path belongs to
    vint<W> path;  ///< each lane's entry in the pass's queue: where its radiance adds up
    vint<W> key, refl_depth, refr_depth, env, pixel;
    vint<W> sample;  ///< the sample index of each lane's path (its random numbers)
    vmask<W> local_only;
};

/// A wavefront holds several samples of a tile's pixels: its sample j at tile slot i (a pixel of
/// the tile) is wavefront slot j * max_block_rays + i.
inline constexpr int tile_slot_bits = 8;
static_assert(max_block_rays == 1 << tile_slot_bits);

/// What a wavefront's slots stand for: the image pixel of each tile slot, and the sample index of
/// the wavefront's first sample (slot s is sample first_sample + s / max_block_rays).
struct SlotMap {
    const int32_t* pixel = nullptr;
    int32_t first_sample = 0;
};

/// Queue entries idx[0..k) of `q` with their hits `h` as shading input (gathers); `slots` maps
/// a slot to its pixel and sample. Lanes from k on are inactive.
template <int W>
inline ShadeInput<W> gather_shade_input(const PathQueue& q, const HitArrays& h,
                                        const SlotMap& slots, const int32_t* idx, vmask<W> active) {
    using namespace shade_detail;
    vint<W> ids;
    if constexpr (W == 1) {
        ids = idx[0];
    } else {
        ids = load<W>(idx);  // idx has room for W entries; lanes past k are masked
    }
    ShadeInput<W> in;
    in.rays.org = {gather_lanes<W>(q.ox, ids, active, 0.0f),
                   gather_lanes<W>(q.oy, ids, active, 0.0f),
                   gather_lanes<W>(q.oz, ids, active, 0.0f)};
    in.rays.dir = {gather_lanes<W>(q.dx, ids, active, 0.0f),
                   gather_lanes<W>(q.dy, ids, active, 0.0f),
                   gather_lanes<W>(q.dz, ids, active, 1.0f)};
    in.hits.t = gather_lanes<W>(h.t, ids, active, 0.0f);
    in.hits.u = gather_lanes<W>(h.u, ids, active, 0.0f);
    in.hits.v = gather_lanes<W>(h.v, ids, active, 0.0f);
    in.hits.prim = gather_lanes<W>(h.prim, ids, active, int32_t{-1});
    in.hits.object = gather_lanes<W>(h.object, ids, active, int32_t{-1});
    in.weight = {gather_lanes<W>(q.wr, ids, active, 0.0f), gather_lanes<W>(q.wg, ids, active, 0.0f),
                 gather_lanes<W>(q.wb, ids, active, 0.0f)};
    in.slot = gather_lanes<W>(q.slot, ids, active, int32_t{0});
    in.path = select(active, ids, vint<W>(0));
    in.key = gather_lanes<W>(q.key, ids, active, int32_t{0});
    in.refl_depth = gather_lanes<W>(q.reflection_depth, ids, active, int32_t{0});
    in.refr_depth = gather_lanes<W>(q.refraction_depth, ids, active, int32_t{0});
    in.env = gather_lanes<W>(q.env_map, ids, active, int32_t{-1});
    in.local_only =
        mask_andnot(active, eq(gather_lanes<W>(q.local_only, ids, active, int32_t{0}), vint<W>(0)));
    const vint<W> tile_slot = in.slot & vint<W>(max_block_rays - 1);
    in.pixel = float_as_int(gather(reinterpret_cast<const float*>(slots.pixel), tile_slot, active));
    in.sample = vint<W>(slots.first_sample) + shift_right_logical<tile_slot_bits>(in.slot);
    return in;
}

}  // namespace raylane::RAYLANE_ISA_NS
