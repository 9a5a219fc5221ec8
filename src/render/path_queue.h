// render: the packet renderer's ray queues - rays of a tile waiting to be traced, one array per
// field (SoA). Grow-only: after a few tiles a thread's queues stop allocating. Used by
// render_packet.cpp and shade/shade_packet.h; the scalar path recurses instead.
#pragma once

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "core/ray.h"

namespace raylane {

/// Slack past the last ray, so W-wide loads at any ray index stay inside the arrays.
inline constexpr size_t pad = 16;

/// Rays of the path tree (camera, mirror, glass and glossy rays) whose radiance, times `weight`,
/// goes to pixel `slot` of the tile. `filter` is Beer's law over the distance to the ray's hit
/// (1 outside glass).
struct PathQueue {
    std::vector<float> ox, oy, oz, dx, dy, dz;
    std::vector<float> wr, wg, wb;
    std::vector<float> fr, fg, fb;
    std::vector<int32_t> slot, key, reflection_depth, refraction_depth, env_map;
    std::vector<uint8_t> local_only;
    int size = 0;

    void clear() { size = 0; }
    /// Makes room for `extra` more rays (grows every array together, by doubling), plus `pad`.
    void reserve_more(int extra) {
        const size_t need = static_cast<size_t>(size + extra);
        if (need + pad <= ox.size()) return;
        const size_t n = std::max(need + pad, 2 * ox.size());
        for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz, &wr, &wg, &wb, &fr, &fg, &fb}) v->resize(n);
        for (auto* v : {&slot, &key, &reflection_depth, &refraction_depth, &env_map}) v->resize(n);
        local_only.resize(n);
    }
    void push(vec3 o, vec3 d, vec3 weight, vec3 filter, int32_t pixel_slot, uint32_t path_key,
              int32_t refl, int32_t refr, int32_t env, bool local) {
        reserve_more(1);
        const size_t i = static_cast<size_t>(size++);
        ox[i] = o.x, oy[i] = o.y, oz[i] = o.z, dx[i] = d.x, dy[i] = d.y, dz[i] = d.z;
        wr[i] = weight.x, wg[i] = weight.y, wb[i] = weight.z;
        fr[i] = filter.x, fg[i] = filter.y, fb[i] = filter.z;
        slot[i] = pixel_slot, key[i] = static_cast<int32_t>(path_key);
        reflection_depth[i] = refl, refraction_depth[i] = refr, env_map[i] = env;
        local_only[i] = local ? 1 : 0;
    }
};

/// Shadow rays towards one light: when the segment (0, t_max) is free, `contribution` is added
/// to pixel `slot`.
struct ShadowQueue {
    std::vector<float> ox, oy, oz, dx, dy, dz, t_max, cr, cg, cb;
    std::vector<int32_t> slot;
    int size = 0;

    void clear() { size = 0; }
    void reserve_more(int extra) {
        const size_t need = static_cast<size_t>(size + extra);
        if (need + pad <= ox.size()) return;
        const size_t n = std::max(need + pad, 2 * ox.size());
        for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz, &t_max, &cr, &cg, &cb}) v->resize(n);
        slot.resize(n);
    }
    void push(vec3 o, vec3 d, float t, vec3 contribution, int32_t pixel_slot) {
        reserve_more(1);
        const size_t i = static_cast<size_t>(size++);
        ox[i] = o.x, oy[i] = o.y, oz[i] = o.z, dx[i] = d.x, dy[i] = d.y, dz[i] = d.z;
        t_max[i] = t;
        cr[i] = contribution.x, cg[i] = contribution.y, cb[i] = contribution.z;
        slot[i] = pixel_slot;
    }
};

}  // namespace raylane
