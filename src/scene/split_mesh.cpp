// scene: one mesh per material (split_mesh.h).
#include "scene/split_mesh.h"

#include <limits>

namespace raylane {

namespace {

/// Copies `from[i]` into `to` the first time index i is seen; returns its new index.
template <class T>
struct Renumber {
    const std::vector<T>& from;
    std::vector<T>& to;
    std::vector<uint32_t> index = std::vector<uint32_t>(from.size(), unused);
    static constexpr uint32_t unused = std::numeric_limits<uint32_t>::max();
    uint32_t operator()(uint32_t i) {
        if (index[i] == unused) {
            index[i] = static_cast<uint32_t>(to.size());
            to.push_back(from[i]);
        }
        return index[i];
    }
    uvec3 operator()(uvec3 t) {
        const uint32_t a = (*this)(t.x), b = (*this)(t.y), c = (*this)(t.z);  // in this order
        return uvec3(a, b, c);
    }
};

/// The triangles of material m as a mesh of their own.
MeshData part_of(const MeshData& mesh, uint32_t m) {
    MeshData part;
    part.name = mesh.name + ":" + mesh.material_names[m];
    part.normal_to_world = mesh.normal_to_world;
    Renumber<vec3> positions{mesh.positions, part.positions};
    Renumber<vec3> normals{mesh.normals, part.normals};
    Renumber<vec2> uvs{mesh.uvs, part.uvs};
    for (size_t i = 0; i < mesh.tris.size(); ++i) {
        if (mesh.tri_material[i] != m) continue;
        part.tris.push_back(positions(mesh.tris[i]));
        if (!mesh.normal_tris.empty()) part.normal_tris.push_back(normals(mesh.normal_tris[i]));
        if (!mesh.uv_tris.empty()) part.uv_tris.push_back(uvs(mesh.uv_tris[i]));
    }
    return part;
}

}  // namespace

std::vector<MeshPart> split_by_material(MeshData mesh) {
    std::vector<MeshPart> parts;
    if (mesh.material_names.empty() || mesh.tri_material.size() != mesh.tris.size()) {
        mesh.material_names.clear(), mesh.tri_material.clear(), mesh.material_libraries.clear();
        parts.push_back({"", std::move(mesh)});
        return parts;
    }
    std::vector<size_t> used(mesh.material_names.size(), 0);
    for (uint32_t m : mesh.tri_material) ++used[m];
    for (uint32_t m = 0; m < mesh.material_names.size(); ++m)
        if (used[m] > 0) parts.push_back({mesh.material_names[m], part_of(mesh, m)});
    parts.front().mesh.dropped_triangles = mesh.dropped_triangles;
    return parts;
}

}  // namespace raylane
