// query: rays_coherent and make_triangle_normals (intersect_batch.h), the parts of the batch
// queries that do not depend on the instruction set.
#include "query/batch_rays.h"

#include "traverse/triangle_scalar.h"

namespace raylane {

bool rays_coherent(const RayArrays& rays, size_t first, size_t count) {
    ConeTest cone;
    for (size_t i = first; i < first + count; ++i) {
        Ray ray;
        if (read_ray(rays, i, ray)) cone.add(ray.dir);
    }
    return cone.inside;
}

TriangleNormals make_triangle_normals(const SceneData& scene) {
    TriangleNormals normals;
    for (const MeshData& mesh : scene.meshes) {
        std::vector<vec3>& n = normals.meshes.emplace_back(mesh.tris.size());
        for (size_t i = 0; i < mesh.tris.size(); ++i) {
            const glm::uvec3 t = mesh.tris[i];
            n[i] = geometry_triangle<float>(mesh.positions[t.x], mesh.positions[t.y],
                                            mesh.positions[t.z], 0.0f, 0.0f)
                       .normal;
        }
    }
    return normals;
}

}  // namespace raylane
