// scene: a mesh whose faces name several materials, as one mesh per material.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace raylane {

/// The triangles of one material: the name the file gave it ("" when it named none).
struct MeshPart {
    std::string material;
    MeshData mesh;
};

/// The triangles of each entry of mesh.material_names (tri_material) as a mesh of its own, in
/// the order of material_names, each with only the vertices, normals and uvs its triangles use
/// (renumbered in order of first use), named "mesh name:material", without material lists. A
/// name no triangle uses gives no part. A mesh without material names is the one part.
std::vector<MeshPart> split_by_material(MeshData mesh);

}  // namespace raylane
