// Tests of scene/split_mesh: a mesh whose faces name several materials as one mesh per material.
#include "scene/split_mesh.h"

#include <gtest/gtest.h>

namespace raylane {
namespace {

/// Two quads sharing an edge (4 triangles), normals and uvs per vertex; triangles 0 and 3 of
/// material "b", 1 and 2 of "a", and a third name no face uses.
MeshData two_quads() {
    MeshData m;
    m.name = "quads";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
    m.normals = std::vector<vec3>(6, vec3(0, 0, 1));
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 0}, {2, 1}};
    m.tris = {{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 2}};
    m.normal_tris = m.tris;
    m.uv_tris = m.tris;
    m.material_names = {"a", "b", "unused"};
    m.tri_material = {1, 0, 0, 1};
    m.dropped_triangles = 2;
    return m;
}

TEST(SplitMesh, OneMeshPerMaterialWithOnlyTheVerticesItUses) {
    const std::vector<MeshPart> parts = split_by_material(two_quads());
    ASSERT_EQ(parts.size(), 2u);  // "unused" gives no part
    EXPECT_EQ(parts[0].material, "a");
    EXPECT_EQ(parts[1].material, "b");
    const MeshData& a = parts[0].mesh;
    EXPECT_EQ(a.name, "quads:a");
    // triangles (0, 2, 3) and (1, 4, 5): vertices renumbered in order of first use
    EXPECT_EQ(a.tris, (std::vector<uvec3>{{0, 1, 2}, {3, 4, 5}}));
    EXPECT_EQ(a.positions, (std::vector<vec3>{
                               {0, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}}));
    EXPECT_EQ(a.uvs[4], vec2(2, 0));
    EXPECT_EQ(a.normal_tris, a.tris);
    EXPECT_EQ(a.uv_tris, a.tris);
    EXPECT_TRUE(a.material_names.empty() && a.tri_material.empty());
    const MeshData& b = parts[1].mesh;
    EXPECT_EQ(b.tris.size(), 2u);
    EXPECT_EQ(b.positions.size(), 4u);  // 0, 1, 2 and 5
    // every triangle kept once, at the same place
    for (const MeshPart& p : parts)
        for (const uvec3& t : p.mesh.tris)
            EXPECT_NE(glm::cross(p.mesh.positions[t.y] - p.mesh.positions[t.x],
                                 p.mesh.positions[t.z] - p.mesh.positions[t.x]),
                      vec3(0.0f));
    EXPECT_EQ(parts[0].mesh.dropped_triangles, 2u);
}

TEST(SplitMesh, AMeshWithoutMaterialNamesIsTheOnePart) {
    MeshData m = two_quads();
    m.material_names.clear();
    m.tri_material.clear();
    const std::vector<MeshPart> parts = split_by_material(m);
    ASSERT_EQ(parts.size(), 1u);
    EXPECT_EQ(parts[0].material, "");
    EXPECT_EQ(parts[0].mesh.tris, m.tris);
    EXPECT_EQ(parts[0].mesh.positions, m.positions);
}

}  // namespace
}  // namespace raylane
