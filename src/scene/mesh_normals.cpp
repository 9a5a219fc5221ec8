// scene: vertex normals for meshes that come without them.
#include "scene/mesh_normals.h"

#include <cmath>

namespace raylane {

void compute_smooth_normals(MeshData& mesh) {
    std::vector<glm::dvec3> sum(mesh.positions.size(), glm::dvec3(0.0));
    for (const uvec3& t : mesh.tris) {
        const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
        const glm::dvec3 n = glm::cross(b - a, c - a);  // length = twice the area
        sum[t.x] += n;
        sum[t.y] += n;
        sum[t.z] += n;
    }
    mesh.normals.resize(sum.size());
    for (size_t i = 0; i < sum.size(); ++i) {
        const double len = glm::length(sum[i]);
        mesh.normals[i] = len > 0.0 && std::isfinite(len) ? vec3(sum[i] / len) : vec3(0.0f);
    }
    mesh.normal_tris = mesh.tris;
}

void drop_normals(MeshData& mesh) {
    mesh.normals.clear();
    mesh.normal_tris.clear();
}

vec3 triangle_dpdu(const MeshData& mesh, uint32_t prim) {
    if (mesh.uv_tris.empty()) return vec3(0.0f);
    const uvec3 t = mesh.tris[prim], ut = mesh.uv_tris[prim];
    const vec3 e1 = mesh.positions[t.y] - mesh.positions[t.x];
    const vec3 e2 = mesh.positions[t.z] - mesh.positions[t.x];
    const vec2 d1 = mesh.uvs[ut.y] - mesh.uvs[ut.x];
    const vec2 d2 = mesh.uvs[ut.z] - mesh.uvs[ut.x];
    const float det = d1.x * d2.y - d1.y * d2.x;
    if (!(std::fabs(det) > 0.0f)) return vec3(0.0f);
    const vec3 dpdu = (d2.y * e1 - d1.y * e2) / det;
    return std::isfinite(dpdu.x + dpdu.y + dpdu.z) ? dpdu : vec3(0.0f);
}

}  // namespace raylane
