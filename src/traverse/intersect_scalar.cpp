// traverse: scalar two-level BVH traversal. Mirrored by intersect_packet.cpp.
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

/// The ray moved into an object's space; t is unchanged because the map is affine.
Ray to_object_space(const Object& object, const Ray& ray) {
    if (!object.has_transform) return ray;
    Ray r = ray;
    r.org = vec3(object.object_from_world * glm::vec4(ray.org, 1.0f));
    r.dir = vec3(object.object_from_world * glm::vec4(ray.dir, 0.0f));
    return r;
}

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

float intersect_analytic(const Scene& scene, const Object& object, const Ray& ray_obj) {
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

void intersect_object_closest(const Scene& scene, const Accel& accel, uint32_t object_index,
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

bool intersect_object_any(const Scene& scene, const Accel& accel, uint32_t object_index,
                          const Ray& ray, TraversalStats& stats) {
    const Object& object = scene.objects[object_index];
    if (!object.casts_shadows) return false;
    if (object.kind == ShapeKind::mesh)
        return intersect_mesh_any(accel.meshes[object.shape], ray, stats);
    ++stats.prims_tested;
    return intersect_analytic(scene, object, to_object_space(object, ray)) < ray.t_max;
}

}  // namespace

Hit intersect_closest(const Scene& scene, const Accel& accel, const Ray& ray,
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

bool intersect_any(const Scene& scene, const Accel& accel, const Ray& ray,
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

namespace {

// surface: the steps of surface_at, in its order; intersect_packet.cpp takes the same steps W
// lanes at a time.

/// A mesh triangle's corners: positions, and vertex normals and uvs when the mesh has them.
struct TriangleCorners {
    vec3 pos[3];
    vec3 nrm[3];  ///< when has_normals
    vec2 tex[3];  ///< when has_uvs
    bool has_normals = false, has_uvs = false;
};

TriangleCorners triangle_corners(const Mesh& mesh, uint32_t prim) {
    TriangleCorners corners;
    const uvec3 tri = mesh.tris[prim];
    for (int k = 0; k < 3; ++k) corners.pos[k] = mesh.positions[tri[k]];
    corners.has_normals = !mesh.normal_tris.empty();
    if (corners.has_normals) {
        const uvec3 nt = mesh.normal_tris[prim];
        for (int k = 0; k < 3; ++k) corners.nrm[k] = mesh.normals[nt[k]];
    }
    corners.has_uvs = !mesh.uv_tris.empty();
    if (corners.has_uvs) {
        const uvec3 ut = mesh.uv_tris[prim];
        for (int k = 0; k < 3; ++k) corners.tex[k] = mesh.uvs[ut[k]];
    }
    return corners;
}

/// The point at barycentrics (u, v, w = 1 - u - v), from them rather than o + t d (numerics.md
/// §3), and the triangle's geometric normal.
void triangle_surface(const TriangleCorners& corners, float u, float v, float w, vec3& position,
                      vec3& geometric_normal) {
    const vec3 a = corners.pos[0], b = corners.pos[1], c = corners.pos[2];
    position = w * a + u * b + v * c;
    geometric_normal = geometry_triangle(a, b, c, u, v).normal;
}

/// The interpolated vertex normal, or the geometric normal when the mesh has none or it has no
/// usable length.
vec3 shading_normal(const TriangleCorners& corners, float u, float v, float w,
                    const vec3& geometric_normal) {
    if (!corners.has_normals) return geometric_normal;
    const vec3 n = w * corners.nrm[0] + u * corners.nrm[1] + v * corners.nrm[2];
    const float len = glm::length(n);
    return len > 0.0f && std::isfinite(len) ? n / len : geometric_normal;
}

/// The interpolated uv, or the barycentrics (u, v) when the mesh has no uvs.
vec2 texture_uv(const TriangleCorners& corners, float u, float v, float w) {
    if (!corners.has_uvs) return vec2(u, v);
    return w * corners.tex[0] + u * corners.tex[1] + v * corners.tex[2];
}

/// An analytic shape's normal and uv at the object-space point p of the ray r (in object space),
/// and p moved back onto the surface. uv only for a material that reads it (spheres and
/// cylinders skip acos and atan2 otherwise).
LocalGeometry analytic_geometry(const Scene& scene, const Object& object, const Ray& r, vec3& p) {
    const Material& m = scene.materials[object.material];
    const bool with_uv = m.texture >= 0 || m.normal_map >= 0;
    LocalGeometry g;
    switch (object.kind) {
        case ShapeKind::sphere: {
            const Sphere& s = scene.spheres[object.shape];
            g = geometry_sphere(s, p, with_uv);
            // back onto the surface: o + t d is off it by the error of t times |d|, which grows
            // with the distance of the origin (numerics.md section 4)
            p = s.center + s.radius * g.normal;
            break;
        }
        case ShapeKind::box: {
            const Box& b = scene.boxes[object.shape];
            g = geometry_box(b, p);
            // onto the face plane the normal names
            for (int k = 0; k < 3; ++k)
                if (g.normal[k] != 0.0f) p[k] = g.normal[k] < 0.0f ? b.lo[k] : b.hi[k];
            break;
        }
        case ShapeKind::cylinder: {
            const Cylinder& c = scene.cylinders[object.shape];
            g = geometry_cylinder(c, p, with_uv);
            // onto the cap plane, or back onto the side at the same height
            if (g.normal.y != 0.0f) {
                p.y = g.normal.y < 0.0f ? 0.0f : c.height;
            } else {
                p.x = c.radius * g.normal.x;
                p.z = c.radius * g.normal.z;
            }
            break;
        }
        case ShapeKind::plane:
            g = geometry_plane(scene.planes[object.shape], p);
            break;
        case ShapeKind::triangle: {
            const Triangle& t = scene.triangles[object.shape];
            float tt, u = 0.0f, v = 0.0f;
            intersect_triangle(make_watertight_ray(r), t.p0, t.p1, t.p2, -infinity, infinity, tt, u,
                               v);
            g = geometry_triangle(t.p0, t.p1, t.p2, u, v);
            break;
        }
        case ShapeKind::mesh:
            break;
    }
    return g;
}

/// An object-space point and normal taken to the world.
void to_world(const Object& object, const vec3& p, const vec3& n, vec3& position, vec3& normal) {
    if (object.has_transform) {
        position = vec3(object.world_from_object * glm::vec4(p, 1.0f));
        const glm::mat3 normal_matrix = glm::transpose(glm::mat3(object.object_from_world));
        normal = glm::normalize(normal_matrix * n);
    } else {
        position = p;
        normal = n;
    }
}

}  // namespace

SurfacePoint surface_at(const Scene& scene, const Ray& ray, const Hit& hit) {
    SurfacePoint sp;
    const Object& object = scene.objects[hit.object];
    sp.material = object.material;
    // mesh
    if (object.kind == ShapeKind::mesh) {
        const TriangleCorners corners = triangle_corners(scene.meshes[object.shape], hit.prim);
        const float u = hit.uv.x, v = hit.uv.y, w = 1.0f - u - v;
        triangle_surface(corners, u, v, w, sp.position, sp.geometric_normal);
        sp.shading_normal = shading_normal(corners, u, v, w, sp.geometric_normal);
        sp.uv = texture_uv(corners, u, v, w);
        return sp;
    }
    // analytic shapes
    const Ray r = to_object_space(object, ray);
    vec3 p = r.org + hit.t * r.dir;
    const LocalGeometry g = analytic_geometry(scene, object, r, p);
    sp.uv = g.uv;
    to_world(object, p, g.normal, sp.position, sp.geometric_normal);
    sp.shading_normal = sp.geometric_normal;
    return sp;
}

}  // namespace raylane
