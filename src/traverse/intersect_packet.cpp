// traverse: packet two-level traversal (blocks of packets: intersect_block.cpp; streams:
// intersect_stream.cpp). Mirrors intersect_scalar.cpp: the same steps, W lanes at a time, each
// lane with its own active flag and interval, except that a mesh is traversed by its wide tree
// (accel/wide_bvh.h): every child box of a node per step, nearest first (see
// intersect_mesh_closest). Both trees have the same leaves, so the answers are the same.
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
void intersect_object_closest(const Scene& scene, const Accel& accel, uint32_t object_index,
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
vmask<W> intersect_object_any(const Scene& scene, const Accel& accel, uint32_t object_index,
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
void intersect_object_closest_from(const Scene& scene, const Accel& accel, uint32_t object,
                                   const RayPacket<W>& rays, vmask<W> active, HitPacket<W>& hit,
                                   WideRef start) {
    intersect_object_closest(scene, accel, object, rays, active, hit,
                             static_cast<vint<W>*>(nullptr), start);
}

template <int W>
vmask<W> intersect_object_any_from(const Scene& scene, const Accel& accel, uint32_t object,
                                   const RayPacket<W>& rays, vmask<W> active, WideRef start) {
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

// Instantiations: the widths of this instruction set (RAYLANE_FOR_EACH_WIDTH, simd/simd.h).
#define RAYLANE_INSTANTIATE(W)                                                                     \
    template HitPacket<W> intersect_closest<W>(const Scene&, const Accel&, const RayPacket<W>&,    \
                                               vmask<W>, vint<W>*);                                \
    template vmask<W> intersect_any<W>(const Scene&, const Accel&, const RayPacket<W>&, vmask<W>); \
    template void intersect_object_closest_from<W>(const Scene&, const Accel&, uint32_t,           \
                                                   const RayPacket<W>&, vmask<W>, HitPacket<W>&,   \
                                                   WideRef);                                       \
    template vmask<W> intersect_object_any_from<W>(const Scene&, const Accel&, uint32_t,           \
                                                   const RayPacket<W>&, vmask<W>, WideRef);        \
    template SurfacePacket<W> surface_at<W>(const Scene&, const RayPacket<W>&,                     \
                                            const HitPacket<W>&, vmask<W>);
RAYLANE_FOR_EACH_WIDTH(RAYLANE_INSTANTIATE)
#undef RAYLANE_INSTANTIATE
#if defined(__AVX2__)  // W = 1 is among the sse4.2 set's widths; the others trace at W = 1 only
                       // the bvh-cost image's single rays (render_packet.cpp)
template HitPacket<1> intersect_closest<1>(const Scene&, const Accel&, const RayPacket<1>&,
                                           vmask<1>, vint<1>*);
#endif

}  // namespace raylane::RAYLANE_ISA_NS
