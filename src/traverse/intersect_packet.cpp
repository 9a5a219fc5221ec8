// traverse: packet two-level traversal (blocks of packets: intersect_block.cpp; streams:
// intersect_stream.cpp). Mirrors intersect_scalar.cpp: the same steps, W lanes at a time, each
// lane with its own active flag and interval, except that a mesh is traversed by its wide tree
// (accel/wide_bvh.h): every child box of a node per step, nearest first (see
// intersect_mesh_closest). Both trees have the same leaves, so the answers are the same. The
// surface at the hits: surface_packet.cpp.
#include "traverse/intersect_packet.h"

#include <limits>

#include "traverse/box_packet.h"
#include "traverse/cylinder_packet.h"
#include "traverse/hit_update_packet.h"
#include "traverse/intersect_scalar.h"
#include "traverse/leaf_packet.h"
#include "traverse/plane_packet.h"
#include "traverse/slab_packet.h"
#include "traverse/sphere_packet.h"
#include "traverse/triangle_packet.h"

namespace raylane::RAYLANE_ISA_NS {

namespace {

/// Analytic shapes: the packet twins of the shape tests; single triangles lane by lane.
template <int W>
vfloat<W> intersect_analytic(const SceneData& scene, const Object& object, const RayPacket<W>& rays,
                             vmask<W> active) {
    switch (object.kind) {
        case ShapeKind::sphere:
            return intersect_sphere<W>(scene.spheres[object.shape], rays, active);
        case ShapeKind::box:
            return intersect_box<W>(scene.boxes[object.shape], rays, active);
        case ShapeKind::cylinder:
            return intersect_cylinder<W>(scene.cylinders[object.shape], rays, active);
        case ShapeKind::plane:
            return intersect_plane<W>(scene.planes[object.shape], rays, active);
        case ShapeKind::triangle: {
            const Triangle& tri = scene.triangles[object.shape];
            const WatertightPacket<W> wr = make_watertight_ray(rays, active);
            vfloat<W> t(infinity), u(0.0f), v(0.0f);
            const vmask<W> hit = intersect_triangle(wr, tri.p0, tri.p1, tri.p2, rays.t_min,
                                                    rays.t_max, t, u, v, active);
            return select(hit, t, vfloat<W>(infinity));
        }
        case ShapeKind::mesh:
            break;
    }
    return vfloat<W>(infinity);
}

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

// mesh: closest hit over one mesh's wide tree (the scalar twin walks the binary tree; both have
// the same leaves), from slot `start` on without testing its box (the root by default: the
// caller knows the lanes reach it). At each wide node every child box is tested;
// the nearest child entered goes on, the others are pushed farthest first with their lanes and
// their nearest entry distance. When popped, a slot goes on with its lanes if that distance is
// still within a lane's limit (the limits only shrink), without testing the box again; a lane
// that entered farther is culled by the next box or triangle test. Every slot that may hold a
// better hit for a lane is visited by that lane, and hits are ordered by (t, object,
// primitive), so the answers are the scalar path's.
template <int W>
void intersect_mesh_closest(const MeshAccel& mesh, uint32_t object, const RayPacket<W>& rays,
                            vmask<W> active, HitPacket<W>& hit, vint<W>* nodes_visited,
                            WideRef start) {
    if (mesh.wide.nodes.empty() || none(active)) return;
    const WatertightPacket<W> wr = make_watertight_ray(rays, active);
    const SlabPacket<W> sr = make_slab_ray(rays);
    const WideNode* nodes = mesh.wide.nodes.data();
    vfloat<W> limit = t_limit(rays, hit);
    WideEntry stack[wide_stack_size];
    int top = 0;
    WideRef ref = start;
    vmask<W> m = active;
    for (;;) {
        if (ref.count > 0) {
            leaf_closest(leaf_tris(mesh, ref), object, wr, rays, m, limit, hit);
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

// mesh: any hit over one mesh's wide tree, from slot `start` on. The children entered are
// visited nearest first;
// t_max does not change, so a popped slot's lanes are those that have not found a hit yet.
template <int W>
vmask<W> intersect_mesh_any(const MeshAccel& mesh, const RayPacket<W>& rays, vmask<W> active,
                            WideRef start) {
    vmask<W> found = mask_and(active, mask_not(active));
    if (mesh.wide.nodes.empty() || none(active)) return found;
    const WatertightPacket<W> wr = make_watertight_ray(rays, active);
    const SlabPacket<W> sr = make_slab_ray(rays);
    const WideNode* nodes = mesh.wide.nodes.data();
    WideEntry stack[wide_stack_size];
    int top = 0;
    WideRef ref = start;
    vmask<W> m = active;
    for (;;) {
        if (ref.count > 0) {
            found = mask_or(found, leaf_any(leaf_tris(mesh, ref), wr, rays, mask_andnot(m, found)));
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

template <int W>
void intersect_object_closest(const SceneData& scene, const Accel& accel, uint32_t object_index,
                              const RayPacket<W>& rays, vmask<W> active, HitPacket<W>& hit,
                              vint<W>* nodes_visited, WideRef start = {}) {
    const Object& object = scene.objects[object_index];
    if (object.kind == ShapeKind::mesh) {
        intersect_mesh_closest(accel.meshes[object.shape], object_index, rays, active, hit,
                               nodes_visited, start);
        return;
    }
    RayPacket<W> r = to_object_space(object, rays);
    r.t_max = t_limit(rays, hit);
    const vfloat<W> t = intersect_analytic(scene, object, r, active);
    const vmask<W> cand = mask_and(active, t < r.t_max);
    const vmask<W> win = better(t, object_index, 0, hit, cand);
    record(hit, win, t, object_index, 0, vfloat<W>(0.0f), vfloat<W>(0.0f));
}

template <int W>
vmask<W> intersect_object_any(const SceneData& scene, const Accel& accel, uint32_t object_index,
                              const RayPacket<W>& rays, vmask<W> active, WideRef start = {}) {
    const Object& object = scene.objects[object_index];
    if (!object.casts_shadows) return vmask<W>(false);
    if (object.kind == ShapeKind::mesh)
        return intersect_mesh_any(accel.meshes[object.shape], rays, active, start);
    const vfloat<W> t = intersect_analytic(scene, object, to_object_space(object, rays), active);
    return mask_and(active, t < rays.t_max);
}

}  // namespace

template <int W>
void intersect_object_closest_from(const SceneData& scene, const Accel& accel, uint32_t object,
                                   const RayPacket<W>& rays, vmask<W> active, HitPacket<W>& hit,
                                   WideRef start) {
    intersect_object_closest(scene, accel, object, rays, active, hit,
                             static_cast<vint<W>*>(nullptr), start);
}

template <int W>
vmask<W> intersect_object_any_from(const SceneData& scene, const Accel& accel, uint32_t object,
                                   const RayPacket<W>& rays, vmask<W> active, WideRef start) {
    return intersect_object_any(scene, accel, object, rays, active, start);
}

template <int W>
HitPacket<W> intersect_closest(const SceneData& scene, const Accel& accel, const RayPacket<W>& rays,
                               vmask<W> active, vint<W>* nodes_visited) {
    HitPacket<W> hit;
    if (none(active)) return hit;
    for (uint32_t object : accel.unbounded)
        intersect_object_closest(scene, accel, object, rays, active, hit, nodes_visited);
    if (!accel.top.nodes.empty()) {
        const SlabPacket<W> sr = make_slab_ray(rays);
        const int lane = first_active(active);
        const int dir_neg[3] = {get(rays.dir.x, lane) < 0.0f, get(rays.dir.y, lane) < 0.0f,
                                get(rays.dir.z, lane) < 0.0f};
        uint32_t stack[traversal_stack_size];
        int top = 0;
        uint32_t node_index = 0;
        for (;;) {
            const BvhNode& node = accel.top.nodes[node_index];
            if (nodes_visited)
                *nodes_visited = select(active, *nodes_visited + vint<W>(1), *nodes_visited);
            vfloat<W> t_near;
            const vec3 lo(node.lo[0], node.lo[1], node.lo[2]);
            const vec3 hi(node.hi[0], node.hi[1], node.hi[2]);
            const vmask<W> m =
                intersect_slab(sr, lo, hi, rays.t_min, t_limit(rays, hit), t_near, active);
            if (any(m)) {
                if (node.is_leaf()) {
                    for (uint32_t k = node.index; k < node.index + node.count; ++k)
                        intersect_object_closest(scene, accel, accel.top.prim_ids[k], rays, m, hit,
                                                 nodes_visited);
                } else if (dir_neg[node.axis]) {
                    stack[top++] = node_index + 1;
                    node_index = node.index;
                    continue;
                } else {
                    stack[top++] = node.index;
                    node_index = node_index + 1;
                    continue;
                }
            }
            if (top == 0) break;
            node_index = stack[--top];
        }
    }
    return hit;
}

template <int W>
vmask<W> intersect_any(const SceneData& scene, const Accel& accel, const RayPacket<W>& rays,
                       vmask<W> active) {
    vmask<W> found = mask_and(active, mask_not(active));
    for (uint32_t object : accel.unbounded) {
        found = mask_or(
            found, intersect_object_any(scene, accel, object, rays, mask_andnot(active, found)));
    }
    vmask<W> open = mask_andnot(active, found);
    if (any(open) && !accel.top.nodes.empty()) {
        const SlabPacket<W> sr = make_slab_ray(rays);
        uint32_t stack[traversal_stack_size];
        int top = 0;
        uint32_t node_index = 0;
        for (;;) {
            const BvhNode& node = accel.top.nodes[node_index];
            vfloat<W> t_near;
            const vec3 lo(node.lo[0], node.lo[1], node.lo[2]);
            const vec3 hi(node.hi[0], node.hi[1], node.hi[2]);
            const vmask<W> m = intersect_slab(sr, lo, hi, rays.t_min, rays.t_max, t_near, open);
            if (any(m)) {
                if (node.is_leaf()) {
                    for (uint32_t k = node.index; k < node.index + node.count; ++k) {
                        const vmask<W> lanes = mask_andnot(m, found);
                        if (none(lanes)) break;
                        found = mask_or(
                            found,
                            intersect_object_any(scene, accel, accel.top.prim_ids[k], rays, lanes));
                    }
                    open = mask_andnot(active, found);
                    if (none(open)) break;
                } else {
                    stack[top++] = node.index;
                    node_index = node_index + 1;
                    continue;
                }
            }
            if (top == 0) break;
            node_index = stack[--top];
        }
    }
    return found;
}

// Instantiations: the widths of this instruction set (RAYLANE_FOR_EACH_WIDTH, simd/simd.h).
#define RAYLANE_INSTANTIATE(W)                                                                   \
    template HitPacket<W> intersect_closest<W>(const SceneData&, const Accel&,                   \
                                               const RayPacket<W>&, vmask<W>, vint<W>*);         \
    template vmask<W> intersect_any<W>(const SceneData&, const Accel&, const RayPacket<W>&,      \
                                       vmask<W>);                                                \
    template void intersect_object_closest_from<W>(const SceneData&, const Accel&, uint32_t,     \
                                                   const RayPacket<W>&, vmask<W>, HitPacket<W>&, \
                                                   WideRef);                                     \
    template vmask<W> intersect_object_any_from<W>(const SceneData&, const Accel&, uint32_t,     \
                                                   const RayPacket<W>&, vmask<W>, WideRef);
RAYLANE_FOR_EACH_WIDTH(RAYLANE_INSTANTIATE)
#undef RAYLANE_INSTANTIATE
#if defined(__AVX2__)  // W = 1 is among the sse4.2 set's widths; the others trace at W = 1 only
                       // the bvh-cost image's single rays (render/aov_packet.cpp)
template HitPacket<1> intersect_closest<1>(const SceneData&, const Accel&, const RayPacket<1>&,
                                           vmask<1>, vint<1>*);
#endif

}  // namespace raylane::RAYLANE_ISA_NS
