// traverse: the surface at W hits, rebuilt from the scene. Mirrors surface_scalar.cpp: the same
// steps, W lanes at a time.
#include "traverse/surface_packet.h"

#include <limits>

#include "traverse/intersect_packet.h"
#include "traverse/plane_packet.h"
#include "traverse/surface_scalar.h"
#include "traverse/triangle_packet.h"

namespace raylane::RAYLANE_ISA_NS {

namespace {

/// Whether surface_at may read a mesh's arrays by 32-bit gathers: every float index (three per
/// triangle or vertex, two per uv) fits an int32. Larger meshes take the lane-by-lane path.
bool gatherable(const MeshData& mesh) {
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
void gather_corners(const MeshData& mesh, const vint<W>& prim, TriangleCorners<W>& corners,
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
void load_corners_by_lane(const SceneData& scene, const HitPacket<W>& hits,
                          TriangleCorners<W>& corners, vint<W>& material, vmask<W> active) {
    alignas(64) float p[3][3][W] = {}, n[3][3][W] = {}, t[3][2][W] = {};
    alignas(64) int32_t materials[W] = {};
    for_each_active(active, [&](int i) {
        const Object& object = scene.objects[static_cast<uint32_t>(get(hits.object, i))];
        materials[i] = static_cast<int32_t>(object.material);
        if (object.kind != ShapeKind::mesh) return;
        corners.mesh_bits |= 1u << i;
        const MeshData& mesh = scene.meshes[object.shape];
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
TriangleCorners<W> triangle_corners(const SceneData& scene, const HitPacket<W>& hits,
                                    vint<W>& material, vmask<W> active) {
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
vmask<W> plane_surface(const SceneData& scene, const RayPacket<W>& rays, const HitPacket<W>& hits,
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
void surface_by_lane(const SceneData& scene, const RayPacket<W>& rays, const HitPacket<W>& hits,
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
SurfacePacket<W> surface_at(const SceneData& scene, const RayPacket<W>& rays,
                            const HitPacket<W>& hits, vmask<W> active) {
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
#define RAYLANE_INSTANTIATE(W)                                                     \
    template SurfacePacket<W> surface_at<W>(const SceneData&, const RayPacket<W>&, \
                                            const HitPacket<W>&, vmask<W>);
RAYLANE_FOR_EACH_WIDTH(RAYLANE_INSTANTIATE)
#undef RAYLANE_INSTANTIATE

}  // namespace raylane::RAYLANE_ISA_NS
