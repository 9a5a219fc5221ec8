// Tests of scene/mesh_normals.cpp.
#include "scene/mesh_normals.h"

#include <gtest/gtest.h>

#include <cmath>

namespace raylane {
namespace {

/// A unit cube's 8 corners and 12 outward-wound triangles.
MeshData cube() {
    MeshData m;
    for (int i = 0; i < 8; ++i) m.positions.push_back(vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    m.tris = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
              {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return m;
}

TEST(MeshNormals, SmoothNormalsPointOutwardFromTheCentre) {
    MeshData m = cube();
    compute_smooth_normals(m);
    ASSERT_EQ(m.normals.size(), 8u);
    ASSERT_EQ(m.normal_tris.size(), m.tris.size());
    for (size_t i = 0; i < 8; ++i) {
        const vec3 outward = glm::normalize(m.positions[i] - vec3(0.5f));
        EXPECT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-6f);
        EXPECT_GT(glm::dot(m.normals[i], outward), 0.5f) << "vertex " << i;
    }
}

TEST(MeshNormals, AreaWeightingFavoursTheLargerFace) {
    // two triangles meeting at vertex 0: a large one in the xy plane, a small one in the xz plane
    MeshData m;
    m.positions = {vec3(0.0f), vec3(10.0f, 0.0f, 0.0f), vec3(0.0f, 10.0f, 0.0f),
                   vec3(0.0f, 0.0f, -1.0f), vec3(1.0f, 0.0f, 0.0f)};
    m.tris = {{0, 1, 2}, {0, 3, 4}};
    compute_smooth_normals(m);
    const vec3 n = m.normals[0];
    // cross products: (0, 0, 100) for the large face, (0, -1, 0) for the small one
    EXPECT_NEAR(n.z, 100.0f / std::sqrt(10001.0f), 1e-6f);
    EXPECT_NEAR(n.y, -1.0f / std::sqrt(10001.0f), 1e-6f);
}

TEST(MeshNormals, DegenerateNeighbourhoodGivesZeroNotNaN) {
    MeshData m;
    m.positions = {vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(2.0f, 0.0f, 0.0f)};
    m.tris = {{0, 1, 2}};
    compute_smooth_normals(m);
    for (const vec3& n : m.normals) EXPECT_EQ(n, vec3(0.0f));
}

}  // namespace
}  // namespace raylane
