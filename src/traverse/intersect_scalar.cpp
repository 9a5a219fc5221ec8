// traverse: scalar two-level BVH traversal. Mirrored by intersect_packet.cpp; the surface at a
// hit: surface_scalar.cpp.
#include "traverse/intersect_scalar.h"

#include <bit>
#include <cmath>
#include <cstdint>

#include "traverse/box_scalar.h"
#include "traverse/cylinder_scalar.h"
#include "traverse/plane_scalar.h"
#include "traverse/slab_scalar.h"
#include "traverse/sphere_scalar.h"
#include "traverse/triangle_scalar.h"

namespace raylane {
namespace {

/// Upper end of the open interval a node or candidate must beat: tie_ulps above the current hit.
/// A triangle lying in a box face can come out a few ulps below the box's near distance, so one
/// ulp would cull its node and a coplanar tie would never reach the (t, object, prim) tie-break
/// (numerics.md section 2); better() still rejects every candidate that is truly farther.
float t_limit(const Ray& ray, const Hit& hit) {
    if (!hit.hit()) return ray.t_max;
    const float up = std::bit_cast<float>(std::bit_cast<int32_t>(std::fabs(hit.t)) + tie_ulps);
    return up < infinity ? up : infinity;
}

bool better(float t, uint32_t object, uint32_t prim, const Hit& hit) {
    if (t != hit.t) return t < hit.t;
    if (object != hit.object) return object < hit.object;
    return prim < hit.prim;
}

float intersect_analytic(const SceneData& scene, const Object& object, const Ray& ray_obj) {
    switch (object.kind) {
        case ShapeKind::sphere:
            return intersect_sphere(scene.spheres[object.shape], ray_obj);
        case ShapeKind::box:
            return intersect_box(scene.boxes[object.shape], ray_obj);
        case ShapeKind::cylinder:
            return intersect_cylinder(scene.cylinders[object.shape], ray_obj);
        case ShapeKind::plane:
            return intersect_plane(scene.planes[object.shape], ray_obj);
        case ShapeKind::triangle: {
            const Triangle& tri = scene.triangles[object.shape];
            float t, u, v;
            const bool hit = intersect_triangle(make_watertight_ray(ray_obj), tri.p0, tri.p1,
                                                tri.p2, ray_obj.t_min, ray_obj.t_max, t, u, v);
            return hit ? t : infinity;
        }
        case ShapeKind::mesh:
            break;
    }
    return infinity;
}

/// Depth-first traversal of a flat binary BVH: every node whose box the ray enters within
/// [t_min, limit()) is visited, the first child first, or the nearer child first by the ray's
/// direction on the node's split axis when `near_first`. `leaf(first, count)` tests a leaf's
/// primitives and returns true to end the traversal; traverse returns whether one did.
template <bool near_first, typename Limit, typename Leaf>
bool traverse(const Bvh& bvh, const Ray& ray, const Limit& limit, const Leaf& leaf,
              TraversalStats& stats) {
    if (bvh.nodes.empty()) return false;
    const SlabRay sr = make_slab_ray(ray);
    const int dir_neg[3] = {ray.dir.x < 0.0f, ray.dir.y < 0.0f, ray.dir.z < 0.0f};
    uint32_t stack[traversal_stack_size];
    int top = 0;
    uint32_t node_index = 0;
    for (;;) {
        const BvhNode& node = bvh.nodes[node_index];
        ++stats.nodes_visited;
        float t_near;
        const vec3 lo(node.lo[0], node.lo[1], node.lo[2]), hi(node.hi[0], node.hi[1], node.hi[2]);
        if (intersect_slab(sr, lo, hi, ray.t_min, limit(), t_near)) {
            if (node.is_leaf()) {
                if (leaf(node.index, node.count)) return true;
            } else if (near_first && dir_neg[node.axis]) {  // second child is nearer
                stack[top++] = node_index + 1;
                node_index = node.index;
                continue;
            } else {
                stack[top++] = node.index;
                node_index = node_index + 1;
                continue;
            }
        }
        if (top == 0) return false;
        node_index = stack[--top];
    }
}

// mesh: closest hit over one mesh's BVH, near child first.
void intersect_mesh_closest(const MeshAccel& mesh, uint32_t object, const Ray& ray, Hit& hit,
                            TraversalStats& stats) {
    const WatertightRay wr = make_watertight_ray(ray);
    auto limit = [&] { return t_limit(ray, hit); };
    auto leaf = [&](uint32_t first, uint32_t count) {
        for (uint32_t k = first; k < first + count; ++k) {
            ++stats.prims_tested;
            const TriangleVerts& tv = mesh.verts[k];
            float t, u, v;
            if (intersect_triangle(wr, tv.a, tv.b, tv.c, ray.t_min, t_limit(ray, hit), t, u, v) &&
                better(t, object, mesh.bvh.prim_ids[k], hit)) {
                hit = {t, mesh.bvh.prim_ids[k], object, vec2(u, v)};
            }
        }
        return false;
    };
    traverse<true>(mesh.bvh, ray, limit, leaf, stats);
}

// mesh: any hit over one mesh's BVH.
bool intersect_mesh_any(const MeshAccel& mesh, const Ray& ray, TraversalStats& stats) {
    const WatertightRay wr = make_watertight_ray(ray);
    auto limit = [&] { return ray.t_max; };
    auto leaf = [&](uint32_t first, uint32_t count) {
        for (uint32_t k = first; k < first + count; ++k) {
            ++stats.prims_tested;
            const TriangleVerts& tv = mesh.verts[k];
            float t, u, v;
            if (intersect_triangle(wr, tv.a, tv.b, tv.c, ray.t_min, ray.t_max, t, u, v))
                return true;
        }
        return false;
    };
    return traverse<false>(mesh.bvh, ray, limit, leaf, stats);
}

void intersect_object_closest(const SceneData& scene, const Accel& accel, uint32_t object_index,
                              const Ray& ray, Hit& hit, TraversalStats& stats) {
    const Object& object = scene.objects[object_index];
    if (object.kind == ShapeKind::mesh) {
        intersect_mesh_closest(accel.meshes[object.shape], object_index, ray, hit, stats);
        return;
    }
    ++stats.prims_tested;
    Ray r = to_object_space(object, ray);
    r.t_max = t_limit(ray, hit);
    const float t = intersect_analytic(scene, object, r);
    if (t < r.t_max && better(t, object_index, 0, hit)) hit = {t, 0, object_index, vec2(0.0f)};
}

bool intersect_object_any(const SceneData& scene, const Accel& accel, uint32_t object_index,
                          const Ray& ray, TraversalStats& stats) {
    const Object& object = scene.objects[object_index];
    if (!object.casts_shadows) return false;
    if (object.kind == ShapeKind::mesh)
        return intersect_mesh_any(accel.meshes[object.shape], ray, stats);
    ++stats.prims_tested;
    return intersect_analytic(scene, object, to_object_space(object, ray)) < ray.t_max;
}

}  // namespace

Hit intersect_closest(const SceneData& scene, const Accel& accel, const Ray& ray,
                      TraversalStats* stats_out) {
    TraversalStats stats;
    Hit hit;
    for (uint32_t object : accel.unbounded)
        intersect_object_closest(scene, accel, object, ray, hit, stats);
    auto limit = [&] { return t_limit(ray, hit); };
    auto leaf = [&](uint32_t first, uint32_t count) {
        for (uint32_t k = first; k < first + count; ++k)
            intersect_object_closest(scene, accel, accel.top.prim_ids[k], ray, hit, stats);
        return false;
    };
    traverse<true>(accel.top, ray, limit, leaf, stats);
    if (stats_out) {
        stats_out->nodes_visited += stats.nodes_visited;
        stats_out->prims_tested += stats.prims_tested;
    }
    return hit;
}

bool intersect_any(const SceneData& scene, const Accel& accel, const Ray& ray,
                   TraversalStats* stats_out) {
    TraversalStats stats;
    bool found = false;
    for (uint32_t object : accel.unbounded) {
        if (intersect_object_any(scene, accel, object, ray, stats)) {
            found = true;
            break;
        }
    }
    if (!found) {
        auto limit = [&] { return ray.t_max; };
        auto leaf = [&](uint32_t first, uint32_t count) {
            for (uint32_t k = first; k < first + count; ++k)
                if (intersect_object_any(scene, accel, accel.top.prim_ids[k], ray, stats))
                    return true;
            return false;
        };
        found = traverse<false>(accel.top, ray, limit, leaf, stats);
    }
    if (stats_out) {
        stats_out->nodes_visited += stats.nodes_visited;
        stats_out->prims_tested += stats.prims_tested;
    }
    return found;
}

}  // namespace raylane
