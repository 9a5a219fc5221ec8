// io: removes triangles that span no area from a freshly loaded mesh.
#include "io/drop_degenerate.h"

#include "core/error.h"
#include "core/triangle_area.h"

namespace raylane {

void drop_zero_area_triangles(MeshData& mesh, const std::string& name_for_errors) {
    const bool has_uv = !mesh.uv_tris.empty(), has_normal = !mesh.normal_tris.empty();
    const bool has_material = !mesh.tri_material.empty();
    size_t kept = 0;
    for (size_t i = 0; i < mesh.tris.size(); ++i) {
        const uvec3 t = mesh.tris[i];
        if (is_zero_area_triangle(mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]))
            continue;
        mesh.tris[kept] = t;
        if (has_uv) mesh.uv_tris[kept] = mesh.uv_tris[i];
        if (has_normal) mesh.normal_tris[kept] = mesh.normal_tris[i];
        if (has_material) mesh.tri_material[kept] = mesh.tri_material[i];
        ++kept;
    }
    mesh.dropped_triangles += mesh.tris.size() - kept;
    mesh.tris.resize(kept);
    if (has_uv) mesh.uv_tris.resize(kept);
    if (has_normal) mesh.normal_tris.resize(kept);
    if (has_material) mesh.tri_material.resize(kept);
    if (kept == 0) throw InputError(name_for_errors + ": every face has zero area");
}

}  // namespace raylane
