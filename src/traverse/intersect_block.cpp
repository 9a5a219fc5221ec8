// traverse: closest-hit and any-hit queries of a block of coherent packets (a tile's camera
// rays, their shadow rays), traversed as a whole: the ranged traversal and the interval culling
// of intersect_block.h. The node and triangle tests are the packets' own (slab_packet.h,
// triangle_packet.h) and hits are kept with the same tie-break (hit_update_packet.h), so every
// lane gets the packet path's answer.
#include "traverse/intersect_block.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "traverse/hit_update_packet.h"
#include "traverse/intersect_packet.h"
#include "traverse/leaf_packet.h"
#include "traverse/slab_packet.h"
#include "traverse/triangle_packet.h"

namespace raylane::RAYLANE_ISA_NS {

namespace {

/// Interval bounds of a block's rays, for culling a node for all of them at once.
struct BlockBounds {
    vec3 org_lo{infinity}, org_hi{-infinity};
    vec3 inv_lo{infinity}, inv_hi{-infinity};
    float t_min = infinity;                  ///< smallest t_min of the active lanes
    float t_max = infinity;                  ///< no lane has a better hit beyond it
    bool usable[3] = {false, false, false};  ///< reciprocals finite and of one sign on this axis
    int dir_neg[3] = {0, 0, 0};              ///< the block's direction signs, for near-first order
    /// The same bounds for block_may_hit, mirrored (coordinates negated on axes of negative
    /// directions: neg) so that every reciprocal is positive; an unusable axis gets origins
    /// [-inf, inf] and reciprocals [1, 1], which bound nothing.
    bool neg[3] = {false, false, false};
    vec3 mirrored_org_lo{-infinity}, mirrored_org_hi{infinity};
    vec3 mirrored_inv_lo{1.0f}, mirrored_inv_hi{1.0f};
    /// A box holding every ray's segment from org + t_min dir to org + t_max dir, widened by a
    /// margin far above rounding; infinite when a lane's t_max is (camera rays). A shadow block
    /// towards a point light has one end point: the light.
    vec3 segment_lo{-infinity}, segment_hi{infinity};
};

template <int W>
BlockBounds make_block_bounds(const RayPacket<W>* rays, const vmask<W>* active, int count) {
    // Lane-wise minima and maxima over the packets first, one horizontal reduction per bound at
    // the end: the same set of active, non-NaN lanes as hmin/hmax per packet, 13 reductions per
    // block instead of 13 per packet. The reciprocals' bounds come from the directions' (below),
    // three divisions per block: a block culled at the root never computes its packets'
    // reciprocals.
    const vfloat<W> inf(infinity), neg_inf(-infinity);
    vfloat<W> t_min = inf, org_lo[3] = {inf, inf, inf}, org_hi[3] = {neg_inf, neg_inf, neg_inf};
    vfloat<W> dir_lo[3] = {inf, inf, inf}, dir_hi[3] = {neg_inf, neg_inf, neg_inf};
    vfloat<W> t_max = neg_inf, end_lo[3] = {inf, inf, inf}, end_hi[3] = {neg_inf, neg_inf, neg_inf};
    vfloat<W> start_lo[3] = {inf, inf, inf}, start_hi[3] = {neg_inf, neg_inf, neg_inf};
    BlockBounds b;
    // the block's direction signs: its first active lane's
    int first = 0;
    while (first < count && none(active[first])) ++first;
    if (first < count) {
        const int lane = first_active(active[first]);
        const vfloat<W>* dir[3] = {&rays[first].dir.x, &rays[first].dir.y, &rays[first].dir.z};
        for (int k = 0; k < 3; ++k) b.dir_neg[k] = 1.0f / get(*dir[k], lane) < 0.0f;
    }
    for (int p = first; p < count; ++p) {
        const vmask<W> m = active[p];
        // min(x, acc) is x < acc ? x : acc (simd/math.h): a NaN lane keeps acc; an inactive
        // packet changes nothing
        auto lo = [&](vfloat<W>& acc, const vfloat<W>& x) { acc = select(m, min(x, acc), acc); };
        auto hi = [&](vfloat<W>& acc, const vfloat<W>& x) { acc = select(m, max(x, acc), acc); };
        lo(t_min, rays[p].t_min);
        hi(t_max, rays[p].t_max);
        const vfloat<W>* org[3] = {&rays[p].org.x, &rays[p].org.y, &rays[p].org.z};
        const vfloat<W>* dir[3] = {&rays[p].dir.x, &rays[p].dir.y, &rays[p].dir.z};
        for (int k = 0; k < 3; ++k) {
            lo(org_lo[k], *org[k]);
            hi(org_hi[k], *org[k]);
            lo(dir_lo[k], *dir[k]);
            hi(dir_hi[k], *dir[k]);
            const vfloat<W> start = *org[k] + *dir[k] * rays[p].t_min;
            const vfloat<W> end = *org[k] + *dir[k] * rays[p].t_max;
            lo(start_lo[k], start);
            hi(start_hi[k], start);
            lo(end_lo[k], end);
            hi(end_hi[k], end);
        }
    }
    b.t_min = hmin(t_min);
    // no lane hits beyond the largest t_max (a NaN t_max hits nothing)
    b.t_max = hmax(t_max);
    const bool segments = std::isfinite(b.t_min) && std::isfinite(b.t_max);
    for (int k = 0; k < 3; ++k) {
        b.org_lo[k] = hmin(org_lo[k]);
        b.org_hi[k] = hmax(org_hi[k]);
        // 1/x is correctly rounded and decreasing on each sign, so over directions of one sign
        // these are exactly the bounds of the lanes' reciprocals. The axis is usable when they
        // are, as the lanes' own were before this shortcut: finite and strictly of one sign.
        // That leaves out a zero or mixed signs (d_lo <= 0 <= d_hi), an infinite or, under
        // flush-to-zero, a huge direction (a reciprocal of +-0; block_may_hit takes the sign
        // from inv_hi) and an axis whose active lanes are all NaN (d_lo = +inf, d_hi = -inf).
        const float d_lo = hmin(dir_lo[k]), d_hi = hmax(dir_hi[k]);
        b.inv_lo[k] = 1.0f / d_hi;
        b.inv_hi[k] = 1.0f / d_lo;
        const bool finite = std::isfinite(b.inv_lo[k]) && std::isfinite(b.inv_hi[k]) &&
                            std::isfinite(b.org_lo[k]) && std::isfinite(b.org_hi[k]);
        const bool positive = d_lo > 0.0f && b.inv_lo[k] > 0.0f;
        const bool negative = d_hi < 0.0f && b.inv_hi[k] < 0.0f;
        b.usable[k] = finite && (positive || negative);
        if (segments) {
            // the margin: far above the rounding of the end points and of a hit point
            const float seg_lo = std::min(hmin(start_lo[k]), hmin(end_lo[k]));
            const float seg_hi = std::max(hmax(start_hi[k]), hmax(end_hi[k]));
            const float margin =
                1e-4f * (std::max(std::fabs(seg_lo), std::fabs(seg_hi)) + (seg_hi - seg_lo));
            if (std::isfinite(margin)) {  // (else the lanes' end points are not all finite)
                b.segment_lo[k] = seg_lo - margin;
                b.segment_hi[k] = seg_hi + margin;
            }
        }
        if (b.usable[k]) {
            b.neg[k] = negative;
            b.mirrored_org_lo[k] = negative ? -b.org_hi[k] : b.org_lo[k];
            b.mirrored_org_hi[k] = negative ? -b.org_lo[k] : b.org_hi[k];
            b.mirrored_inv_lo[k] = negative ? -b.inv_hi[k] : b.inv_lo[k];
            b.mirrored_inv_hi[k] = negative ? -b.inv_lo[k] : b.inv_hi[k];
        }
    }
    return b;
}

/// False only when no ray of the block can touch the box at t in [the block's smallest t_min,
/// its t_max] (a closest-hit block lowers t_max to its largest limit as hits are found):
/// interval arithmetic over the origins and reciprocals, with a relative margin far above float
/// rounding. In the mirrored space every reciprocal is positive, so the smallest entry distance
/// is (lo - largest origin) times the smallest or largest reciprocal by its sign, and the largest
/// exit distance likewise: the products of the four-corner bound that win, branch-free.
bool block_may_hit(const BlockBounds& b, const float lo_box[3], const float hi_box[3],
                   float& t_enter) {
    float t0 = b.t_min, t1 = b.t_max;
    for (int k = 0; k < 3; ++k)
        if (!(lo_box[k] <= b.segment_hi[k] && hi_box[k] >= b.segment_lo[k])) return false;
    for (int k = 0; k < 3; ++k) {
        const float lo = b.neg[k] ? -hi_box[k] : lo_box[k];
        const float hi = b.neg[k] ? -lo_box[k] : hi_box[k];
        const float a = lo - b.mirrored_org_hi[k], c = hi - b.mirrored_org_lo[k];
        const float enter = a * (a < 0.0f ? b.mirrored_inv_hi[k] : b.mirrored_inv_lo[k]);
        const float exit = c * (c < 0.0f ? b.mirrored_inv_lo[k] : b.mirrored_inv_hi[k]);
        t0 = std::max(t0, enter);
        t1 = std::min(t1, exit);
    }
    t_enter = t0;
    const float margin = 1e-4f * (std::fabs(t0) + std::fabs(t1 == infinity ? 0.0f : t1)) + 1e-30f;
    return t0 <= t1 + margin;
}

bool block_may_hit(const BlockBounds& b, const BvhNode& node) {
    float t_enter;
    return block_may_hit(b, node.lo, node.hi, t_enter);
}

/// Whether an entry bound of block_may_hit lies beyond t_max by more than its margin.
bool beyond(float t_enter, float t_max) {
    return t_max != infinity &&
           t_enter > t_max + 1e-4f * (std::fabs(t_enter) + std::fabs(t_max)) + 1e-30f;
}

/// Slots a wide node's box test reads as one vector: all of them where the build has 8-wide
/// vectors, two halves with 4-wide ones.
inline constexpr int slot_width = native_width < wide_arity ? native_width : wide_arity;

/// block_may_hit for every used slot of a wide node, slot_width slots at a time: bit s is set
/// when the block may hit slot s, and t_enter[s] is then a lower bound of the entry distances
/// of the block's rays. The arithmetic is block_may_hit's, slot by slot.
uint32_t block_may_hit_slots(const BlockBounds& b, const WideNode& node,
                             float t_enter[wide_arity]) {
    constexpr int S = slot_width;
    uint32_t entered = 0;
    for (int base = 0; base < node.children; base += S) {
        vfloat<S> t0(b.t_min), t1(b.t_max);
        vmask<S> overlap = vfloat<S>(0.0f) == vfloat<S>(0.0f);
        for (int k = 0; k < 3; ++k) {
            const vfloat<S> node_lo = load<S>(node.lo[k] + base);
            const vfloat<S> node_hi = load<S>(node.hi[k] + base);
            overlap = mask_and(overlap, mask_and(node_lo <= vfloat<S>(b.segment_hi[k]),
                                                 node_hi >= vfloat<S>(b.segment_lo[k])));
            const vfloat<S> lo = b.neg[k] ? -node_hi : node_lo;
            const vfloat<S> hi = b.neg[k] ? -node_lo : node_hi;
            const vfloat<S> a = lo - vfloat<S>(b.mirrored_org_hi[k]);
            const vfloat<S> c = hi - vfloat<S>(b.mirrored_org_lo[k]);
            const vfloat<S> inv_lo(b.mirrored_inv_lo[k]), inv_hi(b.mirrored_inv_hi[k]);
            const vmask<S> a_neg = a < vfloat<S>(0.0f), c_neg = c < vfloat<S>(0.0f);
            const vfloat<S> enter = a * select(a_neg, inv_hi, inv_lo);
            const vfloat<S> exit = c * select(c_neg, inv_lo, inv_hi);
            t0 = max(enter, t0);  // std::max(t0, enter) and std::min(t1, exit), NaN included
            t1 = min(exit, t1);
        }
        const vfloat<S> far = select(t1 == vfloat<S>(infinity), vfloat<S>(0.0f), t1);
        const vfloat<S> margin = vfloat<S>(1e-4f) * (abs(t0) + abs(far)) + vfloat<S>(1e-30f);
        store(t_enter + base, t0);
        entered |= bits(mask_and(overlap, t0 <= t1 + margin)) << base;
    }
    return entered & ((1u << node.children) - 1u);
}

/// The box [lo, hi] under m, as a point (w = 1) or a direction (w = 0): the centre mapped and the
/// half extent by |m|. `mag` bounds the size of the terms summed in each row, the scale of the
/// rounding of to_object_space.
void transform_box(const mat4& m, float w, vec3 lo, vec3 hi, vec3& out_lo, vec3& out_hi,
                   vec3& mag) {
    const vec3 c = 0.5f * (lo + hi), e = 0.5f * (hi - lo);
    const vec3 size = glm::max(glm::abs(lo), glm::abs(hi));
    for (int k = 0; k < 3; ++k) {
        float centre = w * m[3][k], extent = 0.0f, terms = std::fabs(w * m[3][k]);
        for (int j = 0; j < 3; ++j) {
            centre += m[j][k] * c[j];
            extent += std::fabs(m[j][k]) * e[j];
            terms += std::fabs(m[j][k]) * size[j];
        }
        out_lo[k] = centre - extent, out_hi[k] = centre + extent, mag[k] = terms;
    }
}

/// False only when no ray of the block can meet the plane at t >= 0: every origin strictly on
/// one side and every direction strictly away from it, so plane_packet.h's t = S / D is negative
/// (S = n.(point - org), D = n.dir in the object's space). Interval arithmetic over the block's
/// origins and directions (from the reciprocals, on the axes where they have one sign); the
/// margins, 4e-6 of the magnitudes involved, are far above the rounding of the transform and the
/// dot products (a few 1e-7), and far below the offset of a ray leaving the plane (256 ulps).
bool block_may_hit_plane(const BlockBounds& b, const Object& object, const Plane& plane) {
    if (!(b.t_min >= 0.0f)) return true;
    vec3 olo = b.org_lo, ohi = b.org_hi, dlo, dhi;
    for (int k = 0; k < 3; ++k) {
        if (!b.usable[k] && (object.has_transform || plane.normal[k] != 0.0f)) return true;
        dlo[k] = b.usable[k] ? 1.0f / b.inv_hi[k] : 0.0f;
        dhi[k] = b.usable[k] ? 1.0f / b.inv_lo[k] : 0.0f;
    }
    vec3 omag = glm::max(glm::abs(olo), glm::abs(ohi)),
         dmag = glm::max(glm::abs(dlo), glm::abs(dhi));
    if (object.has_transform) {
        transform_box(object.object_from_world, 1.0f, b.org_lo, b.org_hi, olo, ohi, omag);
        const vec3 wlo = dlo, whi = dhi;
        transform_box(object.object_from_world, 0.0f, wlo, whi, dlo, dhi, dmag);
    }
    const vec3 n = plane.normal, p = plane.point;
    float s_lo = 0.0f, s_hi = 0.0f, d_lo = 0.0f, d_hi = 0.0f, s_mag = 0.0f, d_mag = 0.0f;
    for (int k = 0; k < 3; ++k) {
        if (n[k] == 0.0f) continue;  // the bounds of that axis may be infinite
        const float s0 = n[k] * (p[k] - olo[k]), s1 = n[k] * (p[k] - ohi[k]);
        const float d0 = n[k] * dlo[k], d1 = n[k] * dhi[k];
        s_lo += std::min(s0, s1), s_hi += std::max(s0, s1);
        d_lo += std::min(d0, d1), d_hi += std::max(d0, d1);
        s_mag += std::fabs(n[k]) * (std::fabs(p[k]) + omag[k]);
        d_mag += std::fabs(n[k]) * dmag[k];
    }
    const float s_margin = 4e-6f * s_mag, d_margin = 4e-6f * d_mag;
    const bool away =
        (s_hi < -s_margin && d_lo > d_margin) || (s_lo > s_margin && d_hi < -d_margin);
    return !away;
}

/// Whether the unbounded object may be hit by a ray of the block (planes: block_may_hit_plane).
bool block_may_hit_unbounded(const SceneData& scene, const BlockBounds& b, const Object& object) {
    return object.kind != ShapeKind::plane ||
           block_may_hit_plane(b, object, scene.planes[object.shape]);
}

/// Ranged traversal of one BVH by a block of `count` packets. Every range of packets in this file
/// is half-open, [first, end). leaf(node, first, end) is called with the packets [first, end)
/// that may touch the leaf; test(p, node) is packet p's slab mask for the node.
template <int W, class Test, class Leaf>
void traverse_block(const Bvh& bvh, const BlockBounds& bounds, int count, Test&& test,
                    Leaf&& leaf) {
    struct Entry {
        uint32_t node;
        uint16_t first, end;  // packets [first, end)
    };
    Entry stack[traversal_stack_size];
    int top = 0;
    Entry e{0, 0, static_cast<uint16_t>(count)};
    for (;;) {
        const BvhNode& node = bvh.nodes[e.node];
        // first packet that touches the node (interval culling when the first one does not)
        int first = e.first;
        bool touched = any(test(first, node));
        if (!touched && block_may_hit(bounds, node)) {
            for (++first; first < e.end; ++first) {
                if (any(test(first, node))) {
                    touched = true;
                    break;
                }
            }
        }
        if (touched) {
            if (node.is_leaf()) {
                leaf(node, first, int{e.end});  // leaves test each packet of [first, end) anyway
            } else {
                // last packet that touches the node: the children need not look past it
                int last = e.end - 1;
                while (last > first && !any(test(last, node))) --last;
                const uint16_t first16 = static_cast<uint16_t>(first);
                const uint16_t end16 = static_cast<uint16_t>(last + 1);
                if (bounds.dir_neg[node.axis]) {
                    stack[top++] = {e.node + 1, first16, end16};
                    e = {node.index, first16, end16};
                } else {
                    stack[top++] = {node.index, first16, end16};
                    e = {e.node + 1, first16, end16};
                }
                continue;
            }
        }
        if (top == 0) break;
        e = stack[--top];
    }
}

/// Ranged traversal of one mesh's wide tree by a block of `count` packets. At a wide node the
/// block's bounds are tested against every slot at once (block_may_hit_slots); a slot they may
/// hit goes on with the packets from the first to the last whose own test hits it, nearest
/// slot (by the bounds' entry distance) first. test(p, node, s) is packet p's slab mask for
/// slot s of `node`; leaf(node, s, first, end) tests packets [first, end) against the leaf
/// in slot s and returns true when no lane of the block is left open (any hit: the block
/// stops). A popped slot whose entry bound is beyond the block's t_max (lowered by the leaves)
/// is skipped.
template <int W, class Test, class Leaf>
void traverse_block_wide(const WideBvh& wide, const BlockBounds& bounds, int count, Test&& test,
                         Leaf&& leaf) {
    struct Entry {
        uint32_t node;
        uint16_t slot;
        uint16_t first, end;  // packets [first, end)
        float t_enter;
    };
    Entry stack[wide_stack_size + 1];
    int top = 0;
    uint32_t node_index = 0;
    uint16_t first = 0, end = static_cast<uint16_t>(count);
    for (;;) {
        // an interior node: its slots that some packet of [first, end) enters, nearest first
        const WideNode& node = wide.nodes[node_index];
        float t_enter[wide_arity];
        uint32_t slots = block_may_hit_slots(bounds, node, t_enter);
        Entry entered[wide_arity];
        int entered_count = 0;
        for (; slots != 0; slots &= slots - 1) {
            const int s = std::countr_zero(slots);
            // the first and the last packet whose own test hits the slot
            int slot_first = first;
            while (slot_first < end && none(test(slot_first, node, s))) ++slot_first;
            if (slot_first == end) continue;
            int slot_last = end - 1;
            while (slot_last > slot_first && none(test(slot_last, node, s))) --slot_last;
            const Entry e{node_index, static_cast<uint16_t>(s), static_cast<uint16_t>(slot_first),
                          static_cast<uint16_t>(slot_last + 1), t_enter[s]};
            int at = entered_count++;
            for (; at > 0 && entered[at - 1].t_enter > e.t_enter; --at)
                entered[at] = entered[at - 1];
            entered[at] = e;
        }
        for (int i = entered_count - 1; i >= 0; --i) stack[top++] = entered[i];
        // the next interior slot; the leaves on the way are tested
        for (;;) {
            if (top == 0) return;
            const Entry e = stack[--top];
            if (beyond(e.t_enter, bounds.t_max)) continue;
            const WideNode& parent = wide.nodes[e.node];
            if (parent.is_leaf(e.slot)) {
                if (leaf(parent, e.slot, e.first, e.end)) return;
                continue;
            }
            node_index = parent.child[e.slot];
            first = e.first, end = e.end;
            __builtin_prefetch(&wide.nodes[node_index]);
            break;
        }
    }
}

}  // namespace

template <int W>
void intersect_closest_block(const SceneData& scene, const Accel& accel, const RayPacket<W>* rays,
                             const vmask<W>* active, HitPacket<W>* hits, int count) {
    for (int p = 0; p < count; ++p) hits[p] = HitPacket<W>{};
    BlockBounds bounds = make_block_bounds(rays, active, count);
    for (uint32_t object : accel.unbounded) {
        if (!block_may_hit_unbounded(scene, bounds, scene.objects[object])) continue;
        for (int p = 0; p < count; ++p)
            if (any(active[p]))
                intersect_object_closest_from(scene, accel, object, rays[p], active[p], hits[p]);
    }
    // the BVH: only when the block may meet its root box
    if (accel.top.nodes.empty() || !block_may_hit(bounds, accel.top.nodes[0])) return;
    SlabPacket<W> sr[max_block_rays / W];
    vfloat<W> limit[max_block_rays / W];
    for (int p = 0; p < count; ++p) {
        sr[p] = make_slab_ray(rays[p]);
        limit[p] = t_limit(rays[p], hits[p]);
    }
    // the block's bound on t: the smallest of the largest limits of its active lanes seen so
    // far. A better hit lies below a lane's current limit and below each limit it had before
    // (it is nearer than the hit that set the limit; a hit at negative t raises the limit,
    // |t| + 4 ulps, but not the better hits' t), so nodes beyond the bound hold none, and
    // block_may_hit culls them with one test instead of one per packet (most of a covered
    // tile's nodes behind its first hits). Hits of analytic objects in top-level leaves do not
    // lower it: a looser bound, still a bound.
    auto lower_t_max = [&] {
        vfloat<W> far(-infinity);
        for (int p = 0; p < count; ++p) far = select(active[p], max(limit[p], far), far);
        bounds.t_max = std::min(bounds.t_max, hmax(far));
    };
    lower_t_max();
    auto test = [&](int p, const BvhNode& node) {
        vfloat<W> t_near;
        return intersect_slab(sr[p], vec3(node.lo[0], node.lo[1], node.lo[2]),
                              vec3(node.hi[0], node.hi[1], node.hi[2]), rays[p].t_min, limit[p],
                              t_near, active[p]);
    };
    auto test_slot = [&](int p, const WideNode& node, int s) {
        vfloat<W> t_near;
        return intersect_slab(sr[p], vec3(node.lo[0][s], node.lo[1][s], node.lo[2][s]),
                              vec3(node.hi[0][s], node.hi[1][s], node.hi[2][s]), rays[p].t_min,
                              limit[p], t_near, active[p]);
    };
    WatertightPacket<W> wr[max_block_rays / W];
    bool wr_ready[max_block_rays / W] = {};
    bool found = false;
    // the objects of a top-level leaf against the packets [first, end) that may touch it
    auto intersect_top_leaf = [&](const BvhNode& top_leaf, int first, int end) {
        for (uint32_t k = top_leaf.index; k < top_leaf.index + top_leaf.count; ++k) {
            const uint32_t object_index = accel.top.prim_ids[k];
            const Object& object = scene.objects[object_index];
            if (object.kind != ShapeKind::mesh) {
                for (int p = first; p < end; ++p) {
                    const vmask<W> m = test(p, top_leaf);
                    if (any(m)) {
                        intersect_object_closest_from(scene, accel, object_index, rays[p], m,
                                                      hits[p]);
                        limit[p] = t_limit(rays[p], hits[p]);
                    }
                }
                continue;
            }
            // a mesh: the same ranged traversal over its own BVH, for packets [first, end),
            // which it numbers from 0
            const MeshAccel& mesh = accel.meshes[object.shape];
            if (mesh.wide.nodes.empty()) continue;
            for (int p = first; p < end; ++p) {
                if (!wr_ready[p]) fill_watertight_ray(wr[p], rays[p], active[p]);
                wr_ready[p] = true;
            }
            traverse_block_wide<W>(
                mesh.wide, bounds, end - first,
                [&](int mesh_p, const WideNode& node, int s) {
                    return test_slot(first + mesh_p, node, s);
                },
                [&](const WideNode& node, int s, int mesh_first, int mesh_end) {
                    // packets first + [mesh_first, mesh_end)
                    for (int p = first + mesh_first; p < first + mesh_end; ++p) {
                        const vmask<W> m = test_slot(p, node, s);
                        if (none(m)) continue;
                        const LeafTris tris = leaf_tris(mesh, {node.child[s], node.count[s]});
                        if (any(leaf_closest(tris, object_index, wr[p], rays[p], m, limit[p],
                                             hits[p])))
                            found = true;
                    }
                    if (found) lower_t_max();
                    found = false;
                    return false;
                });
        }
    };
    traverse_block<W>(accel.top, bounds, count, test, intersect_top_leaf);
}

template <int W>
void intersect_any_block(const SceneData& scene, const Accel& accel, const RayPacket<W>* rays,
                         const vmask<W>* active, vmask<W>* occluded, int count) {
    for (int p = 0; p < count; ++p) occluded[p] = mask_and(active[p], mask_not(active[p]));
    // the bounds of the active rays, also for the BVH (those the unbounded objects occlude are
    // few: a bound over a few more rays still holds)
    const BlockBounds bounds = make_block_bounds(rays, active, count);
    for (uint32_t object : accel.unbounded) {
        if (!block_may_hit_unbounded(scene, bounds, scene.objects[object])) continue;
        for (int p = 0; p < count; ++p) {
            const vmask<W> lanes = mask_andnot(active[p], occluded[p]);
            if (any(lanes))
                occluded[p] = mask_or(
                    occluded[p], intersect_object_any_from(scene, accel, object, rays[p], lanes));
        }
    }
    // the BVH: only when the block may meet its root box
    if (accel.top.nodes.empty() || !block_may_hit(bounds, accel.top.nodes[0])) return;
    SlabPacket<W> sr[max_block_rays / W];
    vmask<W> open[max_block_rays / W];
    for (int p = 0; p < count; ++p) {
        sr[p] = make_slab_ray(rays[p]);
        open[p] = mask_andnot(active[p], occluded[p]);
    }
    auto test = [&](int p, const BvhNode& node) {
        vfloat<W> t_near;
        return intersect_slab(sr[p], vec3(node.lo[0], node.lo[1], node.lo[2]),
                              vec3(node.hi[0], node.hi[1], node.hi[2]), rays[p].t_min,
                              rays[p].t_max, t_near, open[p]);
    };
    auto test_slot = [&](int p, const WideNode& node, int s) {
        vfloat<W> t_near;
        return intersect_slab(sr[p], vec3(node.lo[0][s], node.lo[1][s], node.lo[2][s]),
                              vec3(node.hi[0][s], node.hi[1][s], node.hi[2][s]), rays[p].t_min,
                              rays[p].t_max, t_near, open[p]);
    };
    WatertightPacket<W> wr[max_block_rays / W];
    bool wr_ready[max_block_rays / W] = {};
    // the objects of a top-level leaf against the packets [first, end) that may touch it
    auto intersect_top_leaf = [&](const BvhNode& top_leaf, int first, int end) {
        for (uint32_t k = top_leaf.index; k < top_leaf.index + top_leaf.count; ++k) {
            const uint32_t object_index = accel.top.prim_ids[k];
            const Object& object = scene.objects[object_index];
            if (object.kind != ShapeKind::mesh) {
                for (int p = first; p < end; ++p) {
                    const vmask<W> m = test(p, top_leaf);
                    if (none(m)) continue;
                    occluded[p] = mask_or(occluded[p], intersect_object_any_from(
                                                           scene, accel, object_index, rays[p], m));
                    open[p] = mask_andnot(active[p], occluded[p]);
                }
                continue;
            }
            const MeshAccel& mesh = accel.meshes[object.shape];
            if (mesh.wide.nodes.empty()) continue;
            for (int p = first; p < end; ++p) {
                if (!wr_ready[p]) fill_watertight_ray(wr[p], rays[p], active[p]);
                wr_ready[p] = true;
            }
            traverse_block_wide<W>(
                mesh.wide, bounds, end - first,
                [&](int mesh_p, const WideNode& node, int s) {
                    return test_slot(first + mesh_p, node, s);
                },
                [&](const WideNode& node, int s, int mesh_first, int mesh_end) {
                    // packets first + [mesh_first, mesh_end)
                    bool done = true;
                    for (int p = first + mesh_first; p < first + mesh_end; ++p) {
                        // the open lanes that touch the leaf
                        const vmask<W> m = test_slot(p, node, s);
                        if (none(m)) continue;
                        const LeafTris tris = leaf_tris(mesh, {node.child[s], node.count[s]});
                        occluded[p] = mask_or(occluded[p], leaf_any(tris, wr[p], rays[p], m));
                        open[p] = mask_andnot(active[p], occluded[p]);
                    }
                    for (int p = first; p < end && done; ++p) done = none(open[p]);
                    return done;
                });
        }
    };
    traverse_block<W>(accel.top, bounds, count, test, intersect_top_leaf);
}

// Instantiations: the widths of this instruction set (RAYLANE_FOR_EACH_WIDTH, simd/simd.h).
#define RAYLANE_INSTANTIATE(W)                                                                    \
    template void intersect_closest_block<W>(const SceneData&, const Accel&, const RayPacket<W>*, \
                                             const vmask<W>*, HitPacket<W>*, int);                \
    template void intersect_any_block<W>(const SceneData&, const Accel&, const RayPacket<W>*,     \
                                         const vmask<W>*, vmask<W>*, int);
RAYLANE_FOR_EACH_WIDTH(RAYLANE_INSTANTIATE)
#undef RAYLANE_INSTANTIATE

}  // namespace raylane::RAYLANE_ISA_NS
