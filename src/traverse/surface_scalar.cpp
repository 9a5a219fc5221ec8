// traverse: the surface at a scalar hit, rebuilt from the scene: position, normals, uv. Mirrored
// by surface_packet.cpp.
#include "traverse/surface_scalar.h"

#include <cmath>

#include "traverse/box_scalar.h"
#include "traverse/cylinder_scalar.h"
#include "traverse/intersect_scalar.h"
#include "traverse/plane_scalar.h"
#include "traverse/sphere_scalar.h"
#include "traverse/triangle_scalar.h"

namespace raylane {

namespace {

// surface: the steps of surface_at, in its order; surface_packet.cpp takes the same steps W lanes
// at a time.

/// A mesh triangle's corners: positions, and vertex normals and uvs when the mesh has them.
struct TriangleCorners {
    vec3 pos[3];
    vec3 nrm[3];  ///< when has_normals
    vec2 tex[3];  ///< when has_uvs
    bool has_normals = false, has_uvs = false;
};

TriangleCorners triangle_corners(const MeshData& mesh, uint32_t prim) {
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
LocalGeometry analytic_geometry(const SceneData& scene, const Object& object, const Ray& r,
                                vec3& p) {
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

SurfacePoint surface_at(const SceneData& scene, const Ray& ray, const Hit& hit) {
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
