// scene: vertex normals for meshes that come without them.
#include "scene/mesh_normals.h"

#include <cmath>

namespace raylane {

void compute_smooth_normals(Mesh& mesh) {
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

void drop_normals(Mesh& mesh) {
    mesh.normals.clear();
    mesh.normal_tris.clear();
}

}  // namespace raylane
