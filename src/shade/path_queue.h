// shade: the packet path's ray queues - rays of a tile waiting to be traced, one array per
// field (SoA). Grow-only: after a few tiles a thread's queues stop allocating. Used by
// render/wavefront_packet.h and shade/shade_io_packet.h; the scalar path recurses instead.
#pragma once

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <numeric>
#include <type_traits>
#include <vector>

#include "core/ray.h"
#include "simd/lanes.h"
#include "simd/vec3.h"

namespace raylane::RAYLANE_ISA_NS {

/// Slack past the last ray, so W-wide loads at any ray index stay inside the arrays.
inline constexpr size_t pad = 16;

/// Rays of the path tree (camera, mirror, glass and glossy rays) whose radiance, times `weight`,
/// goes to `slot` of the wavefront (one sample of one of the tile's pixels). `filter` is Beer's law
/// over the distance to the ray's hit (1 outside glass). `parent` is the entry of the previous
/// pass's queue whose hit spawned the ray (-1 for camera rays).
struct PathQueue {
    std::vector<float> ox, oy, oz, dx, dy, dz;
    std::vector<float> wr, wg, wb;
    std::vector<float> fr, fg, fb;
    std::vector<int32_t> slot, parent, key, reflection_depth, refraction_depth, env_map;
    std::vector<int32_t> local_only;  ///< 1: a glossy ray (its hit spawns nothing)
    int size = 0;

    /// Calls f on every array.
    template <class F>
    void for_each_array(F&& f) {
        for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz, &wr, &wg, &wb, &fr, &fg, &fb}) f(*v);
        for (auto* v :
             {&slot, &parent, &key, &reflection_depth, &refraction_depth, &env_map, &local_only})
            f(*v);
    }
    void clear() { size = 0; }
    /// Makes room for `extra` more rays (grows every array together, by doubling), plus `pad`.
    void reserve_more(int extra) {
        const size_t need = static_cast<size_t>(size + extra);
        if (need + pad <= ox.size()) return;
        const size_t n = std::max(need + pad, 2 * ox.size());
        for_each_array([n](auto& v) { v.resize(n); });
    }
    /// Appends all of `other`'s rays.
    void append(const PathQueue& other) {
        if (other.size == 0) return;
        reserve_more(other.size);
        const size_t at = static_cast<size_t>(size), n = static_cast<size_t>(other.size);
        auto copy = [&](auto& to, const auto& from) {
            std::copy(from.begin(), from.begin() + static_cast<std::ptrdiff_t>(n),
                      to.begin() + static_cast<std::ptrdiff_t>(at));
        };
        copy(ox, other.ox), copy(oy, other.oy), copy(oz, other.oz);
        copy(dx, other.dx), copy(dy, other.dy), copy(dz, other.dz);
        copy(wr, other.wr), copy(wg, other.wg), copy(wb, other.wb);
        copy(fr, other.fr), copy(fg, other.fg), copy(fb, other.fb);
        copy(slot, other.slot), copy(parent, other.parent), copy(key, other.key);
        copy(reflection_depth, other.reflection_depth);
        copy(refraction_depth, other.refraction_depth);
        copy(env_map, other.env_map), copy(local_only, other.local_only);
        size += other.size;
    }
    /// Puts rays `from`..size in the order of their parents (stable: a parent's children in the
    /// order they were queued). A packet of W hits queues its rays kind by kind, each kind lane by
    /// lane; sorted, the queue's order no longer depends on W, nor does the order in which the
    /// paths of one slot add up (render/wavefront_packet.h).
    void sort_by_parent(int from) {
        const auto first = parent.begin() + from, last = parent.begin() + size;
        if (std::is_sorted(first, last)) return;
        thread_local std::vector<int32_t> order;
        order.resize(static_cast<size_t>(size - from));
        std::iota(order.begin(), order.end(), from);
        std::sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {  // (no allocation)
            const int32_t pa = parent[size_t(a)], pb = parent[size_t(b)];
            return pa < pb || (pa == pb && a < b);
        });
        for_each_array([&](auto& v) {
            thread_local std::vector<typename std::decay_t<decltype(v)>::value_type> moved;
            moved.resize(order.size());
            for (size_t i = 0; i < order.size(); ++i) moved[i] = v[size_t(order[i])];
            std::copy(moved.begin(), moved.end(), v.begin() + from);
        });
    }
};

/// Shadow rays towards one light: when the segment (0, t_max) is free, `contribution` is added
/// to path `path` (an entry of the pass's PathQueue).
struct ShadowQueue {
    std::vector<float> ox, oy, oz, dx, dy, dz, t_max, cr, cg, cb;
    std::vector<int32_t> path;
    int size = 0;

    void clear() { size = 0; }
    void reserve_more(int extra) {
        const size_t need = static_cast<size_t>(size + extra);
        if (need + pad <= ox.size()) return;
        const size_t n = std::max(need + pad, 2 * ox.size());
        for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz, &t_max, &cr, &cg, &cb}) v->resize(n);
        path.resize(n);
    }
};

/// Appends the active lanes of a packet of rays to q, in lane order (compress stores).
template <int W>
inline void push_packet(PathQueue& q, const Vec3<W>& o, const Vec3<W>& d, const Vec3<W>& weight,
                        const Vec3<W>& filter, const vint<W>& slot, const vint<W>& parent,
                        const vint<W>& key, const vint<W>& refl, const vint<W>& refr,
                        const vint<W>& env, const vint<W>& local, vmask<W> m) {
    q.reserve_more(W);
    const size_t i = static_cast<size_t>(q.size);
    compress_store(&q.ox[i], o.x, m), compress_store(&q.oy[i], o.y, m);
    compress_store(&q.oz[i], o.z, m), compress_store(&q.dx[i], d.x, m);
    compress_store(&q.dy[i], d.y, m), compress_store(&q.dz[i], d.z, m);
    compress_store(&q.wr[i], weight.x, m), compress_store(&q.wg[i], weight.y, m);
    compress_store(&q.wb[i], weight.z, m), compress_store(&q.fr[i], filter.x, m);
    compress_store(&q.fg[i], filter.y, m), compress_store(&q.fb[i], filter.z, m);
    compress_store(&q.slot[i], slot, m), compress_store(&q.parent[i], parent, m);
    compress_store(&q.key[i], key, m);
    compress_store(&q.reflection_depth[i], refl, m);
    compress_store(&q.refraction_depth[i], refr, m);
    compress_store(&q.env_map[i], env, m), compress_store(&q.local_only[i], local, m);
    q.size += count(m);
}

/// Appends the active lanes of a packet of shadow rays to q.
template <int W>
inline void push_packet(ShadowQueue& q, const Vec3<W>& o, const Vec3<W>& d, const vfloat<W>& t,
                        const Vec3<W>& contribution, const vint<W>& path, vmask<W> m) {
    q.reserve_more(W);
    const size_t i = static_cast<size_t>(q.size);
    compress_store(&q.ox[i], o.x, m), compress_store(&q.oy[i], o.y, m);
    compress_store(&q.oz[i], o.z, m), compress_store(&q.dx[i], d.x, m);
    compress_store(&q.dy[i], d.y, m), compress_store(&q.dz[i], d.z, m);
    compress_store(&q.t_max[i], t, m), compress_store(&q.cr[i], contribution.x, m);
    compress_store(&q.cg[i], contribution.y, m), compress_store(&q.cb[i], contribution.z, m);
    compress_store(&q.path[i], path, m);
    q.size += count(m);
}

}  // namespace raylane::RAYLANE_ISA_NS
