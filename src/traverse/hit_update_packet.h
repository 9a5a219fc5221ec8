// traverse: how a packet's closest hits are kept (the packet twin of intersect_scalar.cpp's
// t_limit and its tie-break): shared by the packet, block and stream traversals.
#pragma once

#include "core/ray_packet.h"
#include "traverse/intersect_scalar.h"

namespace raylane::RAYLANE_ISA_NS {

/// Upper end of the open interval a node or candidate must beat (intersect_scalar.cpp: t_limit):
/// tie_ulps above the current hit, so ties and near-ties reach the (t, object, prim) tie-break.
template <int W>
vfloat<W> t_limit(const RayPacket<W>& rays, const HitPacket<W>& hit) {
    const vfloat<W> inf(infinity);
    const vmask<W> has_hit = hit.t < inf;
    if (none(has_hit)) return rays.t_max;
    const vfloat<W> up = int_as_float(float_as_int(abs(hit.t)) + vint<W>(tie_ulps));
    return select(has_hit, select(up < inf, up, inf), rays.t_max);
}

/// Lanes of `cand` whose candidate (t, object, prim) beats the current hit. Ties in t are rare
/// and decided lane by lane.
template <int W>
vmask<W> better(const vfloat<W>& t, uint32_t object, uint32_t prim, const HitPacket<W>& hit,
                vmask<W> cand) {
    vmask<W> win = mask_and(cand, t < hit.t);
    const vmask<W> tie = mask_and(cand, t == hit.t);
    if (any(tie)) {
        uint32_t win_bits = bits(win);
        for_each_active(tie, [&](int i) {
            const uint32_t o = static_cast<uint32_t>(get(hit.object, i));
            const uint32_t p = static_cast<uint32_t>(get(hit.prim, i));
            if (object < o || (object == o && prim < p)) win_bits |= 1u << i;
        });
        win = mask_from_bits<W>(win_bits);
    }
    return win;
}

template <int W>
void record(HitPacket<W>& hit, vmask<W> win, const vfloat<W>& t, uint32_t object, uint32_t prim,
            const vfloat<W>& u, const vfloat<W>& v) {
    hit.t = select(win, t, hit.t);
    hit.u = select(win, u, hit.u);
    hit.v = select(win, v, hit.v);
    hit.object = select(win, vint<W>(static_cast<int32_t>(object)), hit.object);
    hit.prim = select(win, vint<W>(static_cast<int32_t>(prim)), hit.prim);
}

}  // namespace raylane::RAYLANE_ISA_NS
