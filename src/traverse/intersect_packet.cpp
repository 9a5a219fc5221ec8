// traverse: packet two-level BVH traversal (blocks of packets: intersect_block.cpp; streams:
// intersect_stream.cpp). Mirrors intersect_scalar.cpp: the same steps, W
// lanes at a time, each lane with its own active flag and interval, except that the mesh
// traversals test both children of a node per step and order them by entry distance (see
// intersect_mesh_closest); the answers are the same.
#include "traverse/intersect_packet.h"

#include <limits>

#include "traverse/box_packet.h"
#include "traverse/cylinder_packet.h"
#include "traverse/hit_update_packet.h"
#include "traverse/intersect_scalar.h"
#include "traverse/intersect_wide_packet.h"
#include "traverse/plane_packet.h"
#include "traverse/slab_packet.h"
#include "traverse/sphere_packet.h"
#include "traverse/triangle_packet.h"

namespace raylane {

namespace {

/// The rays moved into an object's space; t is unchanged. Same products and sums as glm's
/// mat4 * vec4 on the scalar path: (c0 x + c1 y) + (c2 z + c3 w).
template <int W>
RayPacket<W> to_object_space(const Object& object, const RayPacket<W>& rays) {
    if (!object.has_transform) return rays;
    const mat4& m = object.object_from_world;
    RayPacket<W> r = rays;
    auto row = [&](int k, const Vec3<W>& p, float w) {
        return (vfloat<W>(m[0][k]) * p.x + vfloat<W>(m[1][k]) * p.y) +
               (vfloat<W>(m[2][k]) * p.z + vfloat<W>(m[3][k] * w));
    };
    r.org = {row(0, rays.org, 1.0f), row(1, rays.org, 1.0f), row(2, rays.org, 1.0f)};
    r.dir = {row(0, rays.dir, 0.0f), row(1, rays.dir, 0.0f), row(2, rays.dir, 0.0f)};
    return r;
}

/// Analytic shapes: the packet twins of the shape tests; single triangles lane by lane.
template <int W>
vfloat<W> intersect_analytic(const Scene& scene, const Object& object, const RayPacket<W>& rays,
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

/// The slab test (slab_packet.h) of W rays against both children of a node. Flattened so that
/// both tests are inlined and their independent dependency chains interleave.
template <int W>
[[gnu::flatten]] inline void intersect_children(const SlabPacket<W>& sr, const BvhNode& first,
                                                const BvhNode& second, const vfloat<W>& t_min,
                                                const vfloat<W>& t_max, vfloat<W>& near_first,
                                                vmask<W>& hit_first, vfloat<W>& near_second,
                                                vmask<W>& hit_second, vmask<W> lanes) {
    hit_first = intersect_slab(sr, vec3(first.lo[0], first.lo[1], first.lo[2]),
                               vec3(first.hi[0], first.hi[1], first.hi[2]), t_min, t_max,
                               near_first, lanes);
    hit_second = intersect_slab(sr, vec3(second.lo[0], second.lo[1], second.lo[2]),
                                vec3(second.hi[0], second.hi[1], second.hi[2]), t_min, t_max,
                                near_second, lanes);
}

/// Whether to visit a node's second child before its first when a packet touches both: when it
/// is the nearer one (by entry distance) for more of the lanes that touch both; on a tie, when
/// the first active lane's direction is negative along the split axis.
template <int W>
bool second_child_first(const BvhNode& node, const int* dir_neg, const vfloat<W>& near_first,
                        vmask<W> hit_first, const vfloat<W>& near_second, vmask<W> hit_second) {
    const vmask<W> both = mask_and(hit_first, hit_second);
    const int second_nearer = count(mask_and(both, near_second < near_first));
    const int first_nearer = count(mask_and(both, near_first < near_second));
    if (second_nearer != first_nearer) return second_nearer > first_nearer;
    return dir_neg[node.axis] != 0;
}

/// A node waiting on the closest-hit stack: the lanes whose slab test passed when it was pushed,
/// with their entry distances (128 bytes at W = 16).
template <int W>
struct ClosestEntry {
    vfloat<W> t_near;
    vmask<W> lanes;
    uint32_t node;
};

// mesh: closest hit over one mesh's BVH. Unlike intersect_scalar.cpp, which tests one node per
// step, both children of a node are tested at once and the one nearer for more lanes (by the
// signs for coherent packets) is visited first; the other is pushed with its lanes' entry
// distances. When popped, its lanes are those whose entry is still within the current limit: the
// slab test's own answer (the exit distances are unchanged and the limit only shrinks), without
// testing the box again. The order only decides how soon the limit shrinks; every node that may
// hold a better hit for a lane is still visited by that lane, so the answers are the scalar
// path's.
template <int W>
void intersect_mesh_closest(const MeshAccel& mesh, uint32_t object, const RayPacket<W>& rays,
                            vmask<W> active, HitPacket<W>& hit, vint<W>* nodes_visited,
                            uint32_t start) {
    if (mesh.bvh.nodes.empty()) return;
    const WatertightPacket<W> wr = make_watertight_ray(rays, active);
    const SlabPacket<W> sr = make_slab_ray(rays);
    const int lane = first_active(active);
    const int dir_neg[3] = {get(rays.dir.x, lane) < 0.0f, get(rays.dir.y, lane) < 0.0f,
                            get(rays.dir.z, lane) < 0.0f};
    // coherent: every active lane has the first one's direction signs, so the order by signs is
    // the near-first order of every lane and the entry distances need not be compared
    const uint32_t act = bits(active);
    auto same_sign = [act](const vfloat<W>& d) {
        const uint32_t neg = bits(d < vfloat<W>(0.0f)) & act;
        return neg == 0 || neg == act;
    };
    const bool coherent = same_sign(rays.dir.x) && same_sign(rays.dir.y) && same_sign(rays.dir.z);
    const BvhNode* nodes = mesh.bvh.nodes.data();
    auto count_tests = [&](int n) {
        if (nodes_visited)
            *nodes_visited = select(active, *nodes_visited + vint<W>(n), *nodes_visited);
    };
    vfloat<W> limit = t_limit(rays, hit);
    count_tests(1);
    vfloat<W> t_root;
    const vec3 root_lo(nodes[0].lo[0], nodes[0].lo[1], nodes[0].lo[2]);
    const vec3 root_hi(nodes[0].hi[0], nodes[0].hi[1], nodes[0].hi[2]);
    vmask<W> m = start != 0
                     ? active
                     : intersect_slab(sr, root_lo, root_hi, rays.t_min, limit, t_root, active);
    ClosestEntry<W> stack[traversal_stack_size];
    int top = 0;
    uint32_t node_index = start;
    while (any(m)) {  // m: the lanes that touch node_index's box
        const BvhNode& node = nodes[node_index];
        if (node.is_leaf()) {
            // leaf
            for (uint32_t k = node.index; k < node.index + node.count; ++k) {
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
            // children: nearer first, the other pushed
            const uint32_t first = node_index + 1, second = node.index;
            vfloat<W> near_first, near_second;
            vmask<W> hit_first, hit_second;
            count_tests(2);
            intersect_children(sr, nodes[first], nodes[second], rays.t_min, limit, near_first,
                               hit_first, near_second, hit_second, m);
            const bool any_first = any(hit_first), any_second = any(hit_second);
            // the next step tests the children of whichever child goes on: ask for their boxes
            // now (the second child of a child is far away in the depth-first order)
            if (any_first && !nodes[first].is_leaf())
                __builtin_prefetch(&nodes[nodes[first].index]);
            if (any_second && !nodes[second].is_leaf())
                __builtin_prefetch(&nodes[nodes[second].index]);
            if (any_first && any_second) {
                const bool second_first =
                    coherent ? dir_neg[node.axis] != 0
                             : second_child_first<W>(node, dir_neg, near_first, hit_first,
                                                     near_second, hit_second);
                if (second_first) {
                    stack[top++] = {near_first, hit_first, first};
                    node_index = second;
                    m = hit_second;
                } else {
                    stack[top++] = {near_second, hit_second, second};
                    node_index = first;
                    m = hit_first;
                }
                continue;
            }
            if (any_first || any_second) {
                node_index = any_first ? first : second;
                m = any_first ? hit_first : hit_second;
                continue;
            }
        }
        // pop the next node that a lane still reaches within its limit
        m = mask_and(active, mask_not(active));
        while (top > 0 && none(m)) {
            const ClosestEntry<W>& e = stack[--top];
            m = mask_and(e.lanes, e.t_near <= limit);
            node_index = e.node;
        }
    }
}

// mesh: any hit. Both children of a node are tested at once, the one nearer along the split axis
// for the first active lane is visited first, the other pushed with its lanes (as bits); t_max
// does not change, so when popped its lanes are those that have not found a hit yet.
template <int W>
vmask<W> intersect_mesh_any(const MeshAccel& mesh, const RayPacket<W>& rays, vmask<W> active,
                            uint32_t start) {
    vmask<W> found = mask_and(active, mask_not(active));
    if (mesh.bvh.nodes.empty()) return found;
    const WatertightPacket<W> wr = make_watertight_ray(rays, active);
    const SlabPacket<W> sr = make_slab_ray(rays);
    const int lane = first_active(active);
    const int dir_neg[3] = {get(rays.dir.x, lane) < 0.0f, get(rays.dir.y, lane) < 0.0f,
                            get(rays.dir.z, lane) < 0.0f};
    const BvhNode* nodes = mesh.bvh.nodes.data();
    vfloat<W> t_root;
    const vec3 root_lo(nodes[0].lo[0], nodes[0].lo[1], nodes[0].lo[2]);
    const vec3 root_hi(nodes[0].hi[0], nodes[0].hi[1], nodes[0].hi[2]);
    vmask<W> m = start != 0
                     ? active
                     : intersect_slab(sr, root_lo, root_hi, rays.t_min, rays.t_max, t_root, active);
    struct Entry {
        uint32_t node;
        uint32_t lanes;
    };
    Entry stack[traversal_stack_size];
    int top = 0;
    uint32_t node_index = start;
    while (any(m)) {  // m: the lanes that touch node_index's box and have not found a hit
        const BvhNode& node = nodes[node_index];
        if (node.is_leaf()) {
            // leaf
            for (uint32_t k = node.index; k < node.index + node.count; ++k) {
                const vmask<W> lanes = mask_andnot(m, found);
                if (none(lanes)) break;
                const TriangleVerts& tv = mesh.verts[k];
                vfloat<W> t(infinity), u(0.0f), v(0.0f);
                found = mask_or(found, intersect_triangle(wr, tv.a, tv.b, tv.c, rays.t_min,
                                                          rays.t_max, t, u, v, lanes));
            }
            if (none(mask_andnot(active, found))) return found;
        } else {
            // children: nearer first, the other pushed
            const uint32_t first = node_index + 1, second = node.index;
            vfloat<W> near_first, near_second;
            vmask<W> hit_first, hit_second;
            intersect_children(sr, nodes[first], nodes[second], rays.t_min, rays.t_max, near_first,
                               hit_first, near_second, hit_second, m);
            const bool any_first = any(hit_first), any_second = any(hit_second);
            if (any_first && any_second) {
                if (dir_neg[node.axis]) {
                    stack[top++] = {first, bits(hit_first)};
                    node_index = second;
                    m = hit_second;
                } else {
                    stack[top++] = {second, bits(hit_second)};
                    node_index = first;
                    m = hit_first;
                }
                continue;
            }
            if (any_first || any_second) {
                node_index = any_first ? first : second;
                m = any_first ? hit_first : hit_second;
                continue;
            }
        }
        // pop the next node that an open lane still touches
        m = mask_and(active, mask_not(active));
        while (top > 0 && none(m)) {
            const Entry& e = stack[--top];
            m = mask_andnot(mask_from_bits<W>(e.lanes), found);
            node_index = e.node;
        }
    }
    return found;
}

template <int W>
void intersect_object_closest(const Scene& scene, const Accel& accel, uint32_t object_index,
                              const RayPacket<W>& rays, vmask<W> active, HitPacket<W>& hit,
                              vint<W>* nodes_visited, uint32_t start = 0) {
    const Object& object = scene.objects[object_index];
    if (object.kind == ShapeKind::mesh) {
        // from the root: the wide tree; from a node of the binary tree (blocks, streams): that
        if (start == 0)
            intersect_mesh_closest_wide(accel.meshes[object.shape], object_index, rays, active, hit,
                                        nodes_visited);
        else
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
vmask<W> intersect_object_any(const Scene& scene, const Accel& accel, uint32_t object_index,
                              const RayPacket<W>& rays, vmask<W> active, uint32_t start = 0) {
    const Object& object = scene.objects[object_index];
    if (!object.casts_shadows) return vmask<W>(false);
    if (object.kind == ShapeKind::mesh)
        return start == 0 ? intersect_mesh_any_wide(accel.meshes[object.shape], rays, active)
                          : intersect_mesh_any(accel.meshes[object.shape], rays, active, start);
    const vfloat<W> t = intersect_analytic(scene, object, to_object_space(object, rays), active);
    return mask_and(active, t < rays.t_max);
}

}  // namespace

template <int W>
void intersect_object_closest_from(const Scene& scene, const Accel& accel, uint32_t object,
                                   const RayPacket<W>& rays, vmask<W> active, HitPacket<W>& hit,
                                   uint32_t start) {
    intersect_object_closest(scene, accel, object, rays, active, hit,
                             static_cast<vint<W>*>(nullptr), start);
}

template <int W>
vmask<W> intersect_object_any_from(const Scene& scene, const Accel& accel, uint32_t object,
                                   const RayPacket<W>& rays, vmask<W> active, uint32_t start) {
    return intersect_object_any(scene, accel, object, rays, active, start);
}

template <int W>
HitPacket<W> intersect_closest(const Scene& scene, const Accel& accel, const RayPacket<W>& rays,
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
vmask<W> intersect_any(const Scene& scene, const Accel& accel, const RayPacket<W>& rays,
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

namespace {

/// Whether surface_at may read a mesh's arrays by 32-bit gathers: every float index (three per
/// triangle or vertex, two per uv) fits an int32. Larger meshes take the lane-by-lane path.
bool gatherable(const Mesh& mesh) {
    static_assert(sizeof(uvec3) == 12 && sizeof(vec3) == 12 && sizeof(vec2) == 8);
    constexpr size_t most = size_t(std::numeric_limits<int32_t>::max()) / 3;
    for (size_t n : {mesh.tris.size(), mesh.positions.size(), mesh.normal_tris.size(),
                     mesh.normals.size(), mesh.uv_tris.size(), mesh.uvs.size()})
        if (n > most) return false;
    return true;
}

// surface: the steps of the scalar surface_at, in its order, W lanes at a time.

/// The lanes' mesh triangles' corners in SoA (the scalar TriangleCorners), and the lanes on a
/// mesh, on a mesh with normals and on a mesh with uvs, as bits.
template <int W>
struct TriangleCorners {
    Vec3<W> pos[3], nrm[3];
    vfloat<W> tex[3][2];
    uint32_t mesh_bits = 0, normal_bits = 0, uv_bits = 0;
};

/// The corners of the active lanes' triangles of one mesh, by vector gathers (gatherable).
template <int W>
void gather_corners(const Mesh& mesh, const vint<W>& prim, TriangleCorners<W>& corners,
                    vmask<W> active) {
    corners.mesh_bits = bits(active);
    // the lanes' triangles' corner indices in `tris`
    auto corner_indices = [&](const std::vector<uvec3>& tris, vint<W>(&corner)[3]) {
        const float* base = reinterpret_cast<const float*>(tris.data());
        const vint<W> at = prim * vint<W>(3);
        for (int c = 0; c < 3; ++c) corner[c] = float_as_int(gather(base, at + vint<W>(c), active));
    };
    // the three corners' vectors of `values` for the index triples in `tris`
    auto corner_vectors = [&](const std::vector<uvec3>& tris, const std::vector<vec3>& values,
                              Vec3<W>(&out)[3]) {
        vint<W> corner[3];
        corner_indices(tris, corner);
        const float* base = reinterpret_cast<const float*>(values.data());
        for (int c = 0; c < 3; ++c) {
            const vint<W> at = corner[c] * vint<W>(3);
            out[c] = {gather(base, at, active), gather(base, at + vint<W>(1), active),
                      gather(base, at + vint<W>(2), active)};
        }
    };
    corner_vectors(mesh.tris, mesh.positions, corners.pos);
    if (!mesh.normal_tris.empty()) {
        corners.normal_bits = corners.mesh_bits;
        corner_vectors(mesh.normal_tris, mesh.normals, corners.nrm);
    }
    if (!mesh.uv_tris.empty()) {
        corners.uv_bits = corners.mesh_bits;
        vint<W> corner[3];
        corner_indices(mesh.uv_tris, corner);
        const float* uvs = reinterpret_cast<const float*>(mesh.uvs.data());
        for (int c = 0; c < 3; ++c) {
            const vint<W> at = corner[c] * vint<W>(2);
            corners.tex[c][0] = gather(uvs, at, active);
            corners.tex[c][1] = gather(uvs, at + vint<W>(1), active);
        }
    }
}

/// The corners of the active lanes' mesh triangles lane by lane (lanes on several objects, or
/// on a mesh too large for gathers), and every active lane's material.
template <int W>
void load_corners_by_lane(const Scene& scene, const HitPacket<W>& hits, TriangleCorners<W>& corners,
                          vint<W>& material, vmask<W> active) {
    alignas(64) float p[3][3][W] = {}, n[3][3][W] = {}, t[3][2][W] = {};
    alignas(64) int32_t materials[W] = {};
    for_each_active(active, [&](int i) {
        const Object& object = scene.objects[static_cast<uint32_t>(get(hits.object, i))];
        materials[i] = static_cast<int32_t>(object.material);
        if (object.kind != ShapeKind::mesh) return;
        corners.mesh_bits |= 1u << i;
        const Mesh& mesh = scene.meshes[object.shape];
        const uint32_t prim = static_cast<uint32_t>(get(hits.prim, i));
        const uvec3 tri = mesh.tris[prim];
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) p[c][k][i] = mesh.positions[tri[c]][k];
        if (!mesh.normal_tris.empty()) {
            corners.normal_bits |= 1u << i;
            const uvec3 nt = mesh.normal_tris[prim];
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 3; ++k) n[c][k][i] = mesh.normals[nt[c]][k];
        }
        if (!mesh.uv_tris.empty()) {
            corners.uv_bits |= 1u << i;
            const uvec3 ut = mesh.uv_tris[prim];
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 2; ++k) t[c][k][i] = mesh.uvs[ut[c]][k];
        }
    });
    material = load<W>(materials);
    for (int c = 0; c < 3; ++c) {
        corners.pos[c] = load_vec3<W>(p[c][0], p[c][1], p[c][2]);
        corners.nrm[c] = load_vec3<W>(n[c][0], n[c][1], n[c][2]);
        corners.tex[c][0] = load<W>(t[c][0]);
        corners.tex[c][1] = load<W>(t[c][1]);
    }
}

/// The corners of the active lanes' mesh triangles (none for lanes on analytic shapes), and the
/// lanes' material (left as it is when they are all on one analytic shape, whose surface_at
/// sets it). One object (the camera pass shades a packet object by object, the wavefront
/// material by material, mostly one object): its material, a mesh's values by vector gathers
/// (while the indices fit an int); else lane by lane.
template <int W>
TriangleCorners<W> triangle_corners(const Scene& scene, const HitPacket<W>& hits, vint<W>& material,
                                    vmask<W> active) {
    TriangleCorners<W> corners;
    const int32_t first_index = get(hits.object, first_active(active));
    const Object& first_object = scene.objects[static_cast<uint32_t>(first_index)];
    const bool one_object =
        bits(mask_and(active, eq(hits.object, vint<W>(first_index)))) == bits(active);
    if (one_object) material = vint<W>(static_cast<int32_t>(first_object.material));
    const bool one_mesh = one_object && first_object.kind == ShapeKind::mesh;
    if (one_mesh && gatherable(scene.meshes[first_object.shape])) {
        gather_corners(scene.meshes[first_object.shape], hits.prim, corners, active);
    } else if (!one_object || one_mesh) {
        load_corners_by_lane(scene, hits, corners, material, active);
    }
    return corners;
}

/// The points at barycentrics (u, v, w = 1 - u - v) and the triangles' geometric normals; for
/// slivers and huge triangles the normal in double, lane by lane (geometry_triangle).
template <int W>
void triangle_surface(const TriangleCorners<W>& corners, const vfloat<W>& u, const vfloat<W>& v,
                      const vfloat<W>& w, Vec3<W>& position, Vec3<W>& geometric_normal,
                      vmask<W> on_mesh) {
    const Vec3<W>&a = corners.pos[0], &b = corners.pos[1], &c = corners.pos[2];
    position = w * a + u * b + v * c;
    const Vec3<W> cr = cross(b - a, c - a);
    geometric_normal = normalize(cr);
    const vfloat<W> n2 = dot(cr, cr);
    const vmask<W> unsafe =
        mask_andnot(on_mesh, mask_and(n2 >= vfloat<W>(std::numeric_limits<float>::min()),
                                      n2 <= vfloat<W>(std::numeric_limits<float>::max())));
    if (any(unsafe)) {
        for_each_active(unsafe, [&](int i) {
            const vec3 d =
                triangle_normal_in_double(get_vec3(a, i), get_vec3(b, i), get_vec3(c, i));
            set(geometric_normal.x, i, d.x), set(geometric_normal.y, i, d.y),
                set(geometric_normal.z, i, d.z);
        });
    }
}

/// The interpolated vertex normals of the lanes with normals, where they have a usable length;
/// the geometric normal elsewhere.
template <int W>
Vec3<W> shading_normal(const TriangleCorners<W>& corners, const vfloat<W>& u, const vfloat<W>& v,
                       const vfloat<W>& w, const Vec3<W>& geometric_normal, vmask<W> with_normals) {
    if (none(with_normals)) return geometric_normal;
    const Vec3<W> n = w * corners.nrm[0] + u * corners.nrm[1] + v * corners.nrm[2];
    const vfloat<W> len = length(n);
    const vmask<W> usable =
        mask_and(mask_and(len > vfloat<W>(0.0f), len < vfloat<W>(infinity)), with_normals);
    return select(usable, n / len, geometric_normal);
}

/// The interpolated uvs of the lanes with uvs; the barycentrics (u, v) elsewhere.
template <int W>
void texture_uv(const TriangleCorners<W>& corners, const vfloat<W>& u, const vfloat<W>& v,
                const vfloat<W>& w, vfloat<W>& tu, vfloat<W>& tv, vmask<W> with_uv) {
    tu = u, tv = v;
    if (none(with_uv)) return;
    tu = select(with_uv, w * corners.tex[0][0] + u * corners.tex[1][0] + v * corners.tex[2][0], u);
    tv = select(with_uv, w * corners.tex[0][1] + u * corners.tex[1][1] + v * corners.tex[2][1], v);
}

/// A plane's uv at the object-space points p (geometry_plane: the frame, constant, then
/// uv = dot(p - point, t1 / t2)); returns its normal. The one analytic shape done W lanes at a
/// time (the floor of most scenes); the others go lane by lane through the scalar surface_at.
template <int W>
vec3 analytic_geometry(const Plane& plane, const Vec3<W>& p, vfloat<W>& u, vfloat<W>& v) {
    const PlaneFrame f = plane_frame(plane);
    const Vec3<W> q = p - make_vec3<W>(plane.point.x, plane.point.y, plane.point.z);
    u = dot(q, make_vec3<W>(f.t1.x, f.t1.y, f.t1.z));
    v = dot(q, make_vec3<W>(f.t2.x, f.t2.y, f.t2.z));
    return f.n;
}

/// Object-space points and a normal shared by the lanes taken to the world. Same products and
/// sums as glm's mat4 * vec4 on the scalar path: (c0 x + c1 y) + (c2 z + c3).
template <int W>
void to_world(const Object& object, const Vec3<W>& p, const vec3& n, Vec3<W>& position,
              vec3& normal) {
    if (object.has_transform) {
        const mat4& m = object.world_from_object;
        auto row = [&](int k) {
            return (vfloat<W>(m[0][k]) * p.x + vfloat<W>(m[1][k]) * p.y) +
                   (vfloat<W>(m[2][k]) * p.z + vfloat<W>(m[3][k]));
        };
        position = {row(0), row(1), row(2)};
        normal = glm::normalize(glm::transpose(glm::mat3(object.object_from_world)) * n);
    } else {
        position = p;
        normal = n;
    }
}

/// When the analytic lanes all hit one plane: their surface W lanes at a time
/// (analytic_geometry, to_world). Returns the analytic lanes still to do.
template <int W>
vmask<W> plane_surface(const Scene& scene, const RayPacket<W>& rays, const HitPacket<W>& hits,
                       SurfacePacket<W>& sp, vmask<W> analytic) {
    const uint32_t first = static_cast<uint32_t>(get(hits.object, first_active(analytic)));
    const Object& object = scene.objects[first];
    const vmask<W> same =
        mask_and(analytic, to_float(hits.object) == vfloat<W>(static_cast<float>(first)));
    if (object.kind != ShapeKind::plane || bits(same) != bits(analytic)) return analytic;
    const RayPacket<W> r = to_object_space(object, rays);
    const Vec3<W> p = r.org + hits.t * r.dir;
    vfloat<W> u, v;
    const vec3 n_object = analytic_geometry(scene.planes[object.shape], p, u, v);
    Vec3<W> position;
    vec3 n;
    to_world(object, p, n_object, position, n);
    const Vec3<W> nw = make_vec3<W>(n.x, n.y, n.z);
    sp.position = select(analytic, position, sp.position);
    sp.geometric_normal = select(analytic, nw, sp.geometric_normal);
    sp.shading_normal = select(analytic, nw, sp.shading_normal);
    sp.u = select(analytic, u, sp.u);
    sp.v = select(analytic, v, sp.v);
    return mask_andnot(analytic, same);
}

/// The active lanes one at a time through the scalar surface_at.
template <int W>
void surface_by_lane(const Scene& scene, const RayPacket<W>& rays, const HitPacket<W>& hits,
                     SurfacePacket<W>& sp, vmask<W> active) {
    for_each_active(active, [&](int i) {
        const SurfacePoint s = surface_at(scene, get_ray(rays, i), get_hit(hits, i));
        set(sp.position.x, i, s.position.x);
        set(sp.position.y, i, s.position.y);
        set(sp.position.z, i, s.position.z);
        set(sp.geometric_normal.x, i, s.geometric_normal.x);
        set(sp.geometric_normal.y, i, s.geometric_normal.y);
        set(sp.geometric_normal.z, i, s.geometric_normal.z);
        set(sp.shading_normal.x, i, s.shading_normal.x);
        set(sp.shading_normal.y, i, s.shading_normal.y);
        set(sp.shading_normal.z, i, s.shading_normal.z);
        set(sp.u, i, s.uv.x);
        set(sp.v, i, s.uv.y);
    });
}

}  // namespace

template <int W>
SurfacePacket<W> surface_at(const Scene& scene, const RayPacket<W>& rays, const HitPacket<W>& hits,
                            vmask<W> active) {
    SurfacePacket<W> sp;
    if (none(active)) return sp;
    // mesh: the scalar formulas, W lanes at a time
    const TriangleCorners<W> corners = triangle_corners(scene, hits, sp.material, active);
    if (corners.mesh_bits != 0) {
        const vmask<W> on_mesh = mask_from_bits<W>(corners.mesh_bits);
        const vfloat<W> u = hits.u, v = hits.v, w = vfloat<W>(1.0f) - u - v;
        Vec3<W> p, ng;
        triangle_surface(corners, u, v, w, p, ng, on_mesh);
        const Vec3<W> ns =
            shading_normal(corners, u, v, w, ng, mask_from_bits<W>(corners.normal_bits));
        vfloat<W> tu, tv;
        texture_uv(corners, u, v, w, tu, tv, mask_from_bits<W>(corners.uv_bits));
        sp.position = select(on_mesh, p, sp.position);
        sp.geometric_normal = select(on_mesh, ng, sp.geometric_normal);
        sp.shading_normal = select(on_mesh, ns, sp.shading_normal);
        sp.u = select(on_mesh, tu, sp.u);
        sp.v = select(on_mesh, tv, sp.v);
    }
    // analytic shapes: a plane shared by all of them W lanes at a time (the floor of most
    // scenes), anything else lane by lane through the scalar surface_at
    vmask<W> analytic = mask_andnot(active, mask_from_bits<W>(corners.mesh_bits));
    if (any(analytic)) analytic = plane_surface(scene, rays, hits, sp, analytic);
    surface_by_lane(scene, rays, hits, sp, analytic);
    return sp;
}

// Instantiations: W = 1 (the packet code at scalar width) and every width this build runs.
template HitPacket<1> intersect_closest<1>(const Scene&, const Accel&, const RayPacket<1>&,
                                           vmask<1>, vint<1>*);
template vmask<1> intersect_any<1>(const Scene&, const Accel&, const RayPacket<1>&, vmask<1>);
template void intersect_object_closest_from<1>(const Scene&, const Accel&, uint32_t,
                                               const RayPacket<1>&, vmask<1>, HitPacket<1>&,
                                               uint32_t);
template vmask<1> intersect_object_any_from<1>(const Scene&, const Accel&, uint32_t,
                                               const RayPacket<1>&, vmask<1>, uint32_t);
template SurfacePacket<1> surface_at<1>(const Scene&, const RayPacket<1>&, const HitPacket<1>&,
                                        vmask<1>);
#if XSIMD_WITH_SSE2
template HitPacket<4> intersect_closest<4>(const Scene&, const Accel&, const RayPacket<4>&,
                                           vmask<4>, vint<4>*);
template vmask<4> intersect_any<4>(const Scene&, const Accel&, const RayPacket<4>&, vmask<4>);
template void intersect_object_closest_from<4>(const Scene&, const Accel&, uint32_t,
                                               const RayPacket<4>&, vmask<4>, HitPacket<4>&,
                                               uint32_t);
template vmask<4> intersect_object_any_from<4>(const Scene&, const Accel&, uint32_t,
                                               const RayPacket<4>&, vmask<4>, uint32_t);
template SurfacePacket<4> surface_at<4>(const Scene&, const RayPacket<4>&, const HitPacket<4>&,
                                        vmask<4>);
#endif
#if XSIMD_WITH_AVX2
template HitPacket<8> intersect_closest<8>(const Scene&, const Accel&, const RayPacket<8>&,
                                           vmask<8>, vint<8>*);
template vmask<8> intersect_any<8>(const Scene&, const Accel&, const RayPacket<8>&, vmask<8>);
template void intersect_object_closest_from<8>(const Scene&, const Accel&, uint32_t,
                                               const RayPacket<8>&, vmask<8>, HitPacket<8>&,
                                               uint32_t);
template vmask<8> intersect_object_any_from<8>(const Scene&, const Accel&, uint32_t,
                                               const RayPacket<8>&, vmask<8>, uint32_t);
template SurfacePacket<8> surface_at<8>(const Scene&, const RayPacket<8>&, const HitPacket<8>&,
                                        vmask<8>);
#endif
#if XSIMD_WITH_AVX512F
template HitPacket<16> intersect_closest<16>(const Scene&, const Accel&, const RayPacket<16>&,
                                             vmask<16>, vint<16>*);
template vmask<16> intersect_any<16>(const Scene&, const Accel&, const RayPacket<16>&, vmask<16>);
template void intersect_object_closest_from<16>(const Scene&, const Accel&, uint32_t,
                                                const RayPacket<16>&, vmask<16>, HitPacket<16>&,
                                                uint32_t);
template vmask<16> intersect_object_any_from<16>(const Scene&, const Accel&, uint32_t,
                                                 const RayPacket<16>&, vmask<16>, uint32_t);
template SurfacePacket<16> surface_at<16>(const Scene&, const RayPacket<16>&, const HitPacket<16>&,
                                          vmask<16>);
#endif

}  // namespace raylane
