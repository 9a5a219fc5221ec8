// tests for scene/transform.cpp: rotation handedness, the T * R * S order, exact inverses, the
// "fit" normalisation, and baking into meshes (normals under non-uniform scale and mirrors).
#include "scene/transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace raylane {
namespace {

glm::dvec3 apply(const glm::dmat4& m, glm::dvec3 p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); }

void expect_dvec3_near(glm::dvec3 a, glm::dvec3 b, double tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Transform, RotationsAreRightHandedAndExactAtQuarterTurns) {
    // Exact: no cos(pi/2) residue at multiples of 90 degrees.
    EXPECT_EQ(make_rotation(1, 90.0) * glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1));
    EXPECT_EQ(make_rotation(0, 90.0) * glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1));
    EXPECT_EQ(make_rotation(2, 90.0) * glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0));
    EXPECT_EQ(make_rotation(2, -270.0) * glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0));
    EXPECT_EQ(make_rotation(1, 180.0) * glm::dvec3(1, 2, 3), glm::dvec3(-1, 2, -3));
    // General angle: Ry(a) maps +x to (cos a, 0, -sin a).
    double a = 37.0 * M_PI / 180.0;
    expect_dvec3_near(make_rotation(1, 37.0) * glm::dvec3(1, 0, 0),
                      glm::dvec3(std::cos(a), 0, -std::sin(a)), 1e-15);
    EXPECT_NEAR(glm::determinant(make_rotation(0, 123.0)), 1.0, 1e-15);
}

TEST(Transform, RotationXyzAppliesXThenYThenZ) {
    // Rx(90): +y -> +z; Ry(90): +z -> +x; Rz(90): +x -> +y.
    EXPECT_EQ(make_rotation_xyz(glm::dvec3(90, 90, 90)) * glm::dvec3(0, 1, 0), glm::dvec3(0, 1, 0));
    EXPECT_EQ(make_rotation_xyz(glm::dvec3(90, 90, 0)) * glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0));
}

TEST(Transform, ScalesThenRotatesThenTranslates) {
    Transform t;
    t.translate = glm::dvec3(10, 20, 30);
    t.rotate = make_rotation(2, 90.0);  // (x, y, z) -> (-y, x, z)
    t.scale = glm::dvec3(2, 3, 4);
    // (1, 2, 3) -> (2, 6, 12) -> (-6, 2, 12) -> (4, 22, 42)
    EXPECT_EQ(apply(make_world_from_object(t), glm::dvec3(1, 2, 3)), glm::dvec3(4, 22, 42));
    expect_dvec3_near(apply(make_object_from_world(t), glm::dvec3(4, 22, 42)), glm::dvec3(1, 2, 3),
                      1e-14);
}

TEST(Transform, ObjectFromWorldIsTheInverse) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-5.0, 5.0);
    for (int i = 0; i < 100; ++i) {
        Transform t;
        t.translate = glm::dvec3(u(rng), u(rng), u(rng));
        t.rotate = make_rotation_xyz(glm::dvec3(u(rng), u(rng), u(rng)) * 36.0);
        t.scale = glm::dvec3(u(rng), u(rng), u(rng));
        glm::dmat4 product = make_object_from_world(t) * make_world_from_object(t);
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) {
                double tol = 1e-12 * (1.0 + 1.0 / std::abs(t.scale.x * t.scale.y * t.scale.z));
                EXPECT_NEAR(product[c][r], c == r ? 1.0 : 0.0, tol);
            }
        }
    }
}

TEST(Transform, SetTransformMarksOnlyNonIdentityTransforms) {
    Object o;
    set_transform(o, Transform{});
    EXPECT_FALSE(o.has_transform);
    EXPECT_EQ(o.world_from_object, mat4(1.0f));
    Transform t;
    t.scale = glm::dvec3(1, 1, -1);
    set_transform(o, t);
    EXPECT_TRUE(o.has_transform);
    EXPECT_EQ(vec3(o.world_from_object * glm::vec4(1, 2, 3, 1)), vec3(1, 2, -3));
    EXPECT_EQ(vec3(o.object_from_world * glm::vec4(1, 2, -3, 1)), vec3(1, 2, 3));
}

TEST(Transform, FitMovesTheBottomCentreToTheOffsetAndScalesUniformly) {
    Aabb b;
    b.grow(vec3(-1, 2, 3));
    b.grow(vec3(3, 4, 7));
    glm::dmat4 m = make_fit(b, 2.0, glm::dvec3(5, 0, 0));
    EXPECT_EQ(apply(m, glm::dvec3(1, 2, 5)), glm::dvec3(5, 0, 0));  // bottom centre
    EXPECT_EQ(apply(m, glm::dvec3(3, 4, 7)), glm::dvec3(9, 4, 4));
    EXPECT_EQ(apply(m, glm::dvec3(-1, 2, 3)), glm::dvec3(1, 0, -4));
}

/// A mesh of one tilted triangle with its unit face normal on every vertex.
MeshData make_tilted_triangle() {
    MeshData m;
    m.positions = {vec3(0, 0, 0), vec3(1, 0.5f, 0.2f), vec3(0.3f, 1, 0.7f)};
    vec3 n = glm::normalize(
        glm::cross(m.positions[1] - m.positions[0], m.positions[2] - m.positions[0]));
    m.normals = {n, n, n};
    m.tris = {uvec3(0, 1, 2)};
    m.normal_tris = {uvec3(0, 1, 2)};
    return m;
}

TEST(Transform, BakedNormalsStayPerpendicularUnderNonUniformScale) {
    MeshData m = make_tilted_triangle();
    Transform t;
    t.translate = glm::dvec3(1, -2, 3);
    t.rotate = make_rotation_xyz(glm::dvec3(20, -75, 40));
    t.scale = glm::dvec3(1, 5, 0.2);
    bake_transform(m, make_world_from_object(t));
    vec3 e1 = m.positions[1] - m.positions[0];
    vec3 e2 = m.positions[2] - m.positions[0];
    vec3 face = glm::normalize(glm::cross(e1, e2));
    for (vec3 n : m.normals) {
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(n, e1) / glm::length(e1), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(n, e2) / glm::length(e2), 0.0f, 1e-6f);
        EXPECT_GT(glm::dot(n, face), 0.999f);  // same side as the winding
    }
    expect_dvec3_near(glm::dvec3(m.positions[1]),
                      apply(make_world_from_object(t), glm::dvec3(1, 0.5, 0.2)), 1e-6);
}

TEST(Transform, MirrorReversesTheWindingToMatchTheNormals) {
    MeshData m = make_tilted_triangle();
    m.uvs = {vec2(0, 0), vec2(1, 0), vec2(0, 1)};
    m.uv_tris = {uvec3(0, 1, 2)};
    Transform t;
    t.scale = glm::dvec3(-2, 1, 1);
    bake_transform(m, make_world_from_object(t));
    EXPECT_EQ(m.tris[0], uvec3(0, 2, 1));
    EXPECT_EQ(m.normal_tris[0], uvec3(0, 2, 1));
    EXPECT_EQ(m.uv_tris[0], uvec3(0, 2, 1));
    const uvec3 tri = m.tris[0];
    vec3 face = glm::normalize(glm::cross(m.positions[tri.y] - m.positions[tri.x],
                                          m.positions[tri.z] - m.positions[tri.x]));
    EXPECT_GT(glm::dot(m.normals[0], face), 0.999f);
    EXPECT_EQ(m.positions[1], vec3(-2, 0.5f, 0.2f));
}

TEST(Transform, ZeroNormalStaysZero) {
    MeshData m = make_tilted_triangle();
    m.normals[1] = vec3(0.0f);
    Transform t;
    t.scale = glm::dvec3(3, 1, 1);
    bake_transform(m, make_world_from_object(t));
    EXPECT_EQ(m.normals[1], vec3(0.0f));
    EXPECT_NEAR(glm::length(m.normals[0]), 1.0f, 1e-6f);
}

TEST(Transform, MeshBoundsCoverEveryPosition) {
    MeshData m = make_tilted_triangle();
    Aabb b = mesh_bounds(m);
    EXPECT_EQ(b.lo, vec3(0, 0, 0));
    EXPECT_EQ(b.hi, vec3(1, 1, 0.7f));
    EXPECT_TRUE(mesh_bounds(MeshData{}).empty());
}

}  // namespace
}  // namespace raylane
