// traverse: one packet of W rays through one mesh's wide tree (accel/wide_bvh.h), closest hit
// and any hit: the packet path's mesh traversal. The scalar path walks the binary tree
// (intersect_scalar.cpp); both trees have the same leaves and the triangle test is the same
// arithmetic, so the answers are the same.
#pragma once

#include "accel/bvh.h"
#include "core/ray_packet.h"
#include "traverse/hit_update_packet.h"
#include "traverse/slab_packet.h"
#include "traverse/triangle_packet.h"

namespace raylane {

/// Entries of a wide traversal's stack: each level pushes at most wide_arity - 1 children.
inline constexpr int wide_stack_size = traversal_stack_size * (wide_arity - 1);

/// A slot of a wide node: a wide node (count 0) or a leaf's triangles child .. child + count - 1.
struct WideRef {
    uint32_t child = 0;
    uint32_t count = 0;
};

/// Asks for a wide node's four cache lines.
inline void prefetch_node(const WideNode* node) {
    const char* p = reinterpret_cast<const char*>(node);
    for (int line = 0; line < int(sizeof(WideNode)); line += 64) __builtin_prefetch(p + line);
}

/// A slot entered by some lanes: where it leads, those lanes (bits), and the smallest entry
/// distance among them.
struct WideEntry {
    WideRef ref;
    uint32_t lanes = 0;
    float t_near = 0.0f;
};

/// The slots of `node` that lanes of `m` enter within [t_min, limit), nearest first (by the
/// smallest entry distance of their lanes). Returns how many.
template <int W>
[[gnu::always_inline]] inline int enter_children(const WideNode& node, const SlabPacket<W>& sr,
                                                 const vfloat<W>& t_min, const vfloat<W>& limit,
                                                 vmask<W> m, WideEntry* entered) {
    int n = 0;
    for (int k = 0; k < node.children; ++k) {
        vfloat<W> near;
        const vmask<W> h = intersect_slab(sr, vec3(node.lo[0][k], node.lo[1][k], node.lo[2][k]),
                                          vec3(node.hi[0][k], node.hi[1][k], node.hi[2][k]), t_min,
                                          limit, near, m);
        if (none(h)) continue;
        // insertion by entry distance: a node has at most wide_arity slots
        const WideEntry e{{node.child[k], node.count[k]}, bits(h), hmin(near, h)};
        int at = n++;
        for (; at > 0 && entered[at - 1].t_near > e.t_near; --at) entered[at] = entered[at - 1];
        entered[at] = e;
    }
    return n;
}

// mesh: closest hit over one mesh's wide tree. At each wide node every child box is tested;
// the nearest child entered goes on, the others are pushed farthest first with their lanes and
// their nearest entry distance. When popped, a slot goes on with its lanes if that distance is
// still within a lane's limit (the limits only shrink), without testing the box again; a lane
// that entered farther is culled by the next box or triangle test. Every slot that may hold a
// better hit for a lane is visited by that lane, and hits are ordered by (t, object,
// primitive), so the answers are the scalar path's.
template <int W>
void intersect_mesh_closest_wide(const MeshAccel& mesh, uint32_t object, const RayPacket<W>& rays,
                                 vmask<W> active, HitPacket<W>& hit, vint<W>* nodes_visited) {
    if (mesh.wide.nodes.empty() || none(active)) return;
    const WatertightPacket<W> wr = make_watertight_ray(rays, active);
    const SlabPacket<W> sr = make_slab_ray(rays);
    const WideNode* nodes = mesh.wide.nodes.data();
    vfloat<W> limit = t_limit(rays, hit);
    WideEntry stack[wide_stack_size];
    int top = 0;
    WideRef ref;  // the root
    vmask<W> m = active;
    for (;;) {
        if (ref.count > 0) {
            // leaf
            for (uint32_t k = ref.child; k < ref.child + ref.count; ++k) {
                const TriangleVerts& tv = mesh.verts[k];
                vfloat<W> t(infinity), u(0.0f), v(0.0f);
                const vmask<W> h =
                    intersect_triangle(wr, tv.a, tv.b, tv.c, rays.t_min, limit, t, u, v, m);
                if (any(h)) {
                    const uint32_t prim = mesh.bvh.prim_ids[k];
                    const vmask<W> win = better(t, object, prim, hit, h);
                    record(hit, win, t, object, prim, u, v);
                    limit = t_limit(rays, hit);
                }
            }
        } else {
            // children: the nearest goes on, the others pushed, farthest first
            const WideNode& node = nodes[ref.child];
            if (nodes_visited)
                *nodes_visited =
                    select(active, *nodes_visited + vint<W>(node.children), *nodes_visited);
            WideEntry entered[wide_arity];
            const int n = enter_children(node, sr, rays.t_min, limit, m, entered);
            for (int i = 0; i < n && i < 2; ++i)  // the next nodes' boxes: four cache lines each
                if (entered[i].ref.count == 0) prefetch_node(nodes + entered[i].ref.child);
            if (n > 0) {
                for (int i = n - 1; i > 0; --i) stack[top++] = entered[i];
                ref = entered[0].ref;
                m = mask_from_bits<W>(entered[0].lanes);
                continue;
            }
        }
        // pop the next slot that a lane may still reach within its limit
        m = mask_and(active, mask_not(active));
        while (top > 0 && none(m)) {
            const WideEntry& e = stack[--top];
            m = mask_and(mask_from_bits<W>(e.lanes), vfloat<W>(e.t_near) <= limit);
            ref = e.ref;
        }
        if (none(m)) return;
    }
}

// mesh: any hit over one mesh's wide tree. The children entered are visited nearest first;
// t_max does not change, so a popped slot's lanes are those that have not found a hit yet.
template <int W>
vmask<W> intersect_mesh_any_wide(const MeshAccel& mesh, const RayPacket<W>& rays, vmask<W> active) {
    vmask<W> found = mask_and(active, mask_not(active));
    if (mesh.wide.nodes.empty() || none(active)) return found;
    const WatertightPacket<W> wr = make_watertight_ray(rays, active);
    const SlabPacket<W> sr = make_slab_ray(rays);
    const WideNode* nodes = mesh.wide.nodes.data();
    WideEntry stack[wide_stack_size];
    int top = 0;
    WideRef ref;  // the root
    vmask<W> m = active;
    for (;;) {
        if (ref.count > 0) {
            // leaf
            for (uint32_t k = ref.child; k < ref.child + ref.count; ++k) {
                const vmask<W> lanes = mask_andnot(m, found);
                if (none(lanes)) break;
                const TriangleVerts& tv = mesh.verts[k];
                vfloat<W> t(infinity), u(0.0f), v(0.0f);
                found = mask_or(found, intersect_triangle(wr, tv.a, tv.b, tv.c, rays.t_min,
                                                          rays.t_max, t, u, v, lanes));
            }
            if (none(mask_andnot(active, found))) return found;
        } else {
            // children: the nearest goes on, the others pushed, farthest first
            WideEntry entered[wide_arity];
            const int n = enter_children(nodes[ref.child], sr, rays.t_min, rays.t_max, m, entered);
            for (int i = 0; i < n && i < 2; ++i)
                if (entered[i].ref.count == 0) prefetch_node(nodes + entered[i].ref.child);
            if (n > 0) {
                for (int i = n - 1; i > 0; --i) stack[top++] = entered[i];
                ref = entered[0].ref;
                m = mask_andnot(mask_from_bits<W>(entered[0].lanes), found);
                continue;
            }
        }
        // pop the next slot that an open lane still enters
        m = mask_and(active, mask_not(active));
        while (top > 0 && none(m)) {
            const WideEntry& e = stack[--top];
            m = mask_andnot(mask_from_bits<W>(e.lanes), found);
            ref = e.ref;
        }
        if (none(m)) return found;
    }
}

}  // namespace raylane
