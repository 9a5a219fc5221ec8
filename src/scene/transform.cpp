// scene: object transforms (see transform.h). Matrices are built and composed in double and
// rounded to float once, where they are stored.
#include "scene/transform.h"

#include <cmath>
#include <numbers>
#include <utility>

namespace raylane {

namespace {

/// cos and sin of `deg` degrees; exact (0, +-1) at multiples of 90 degrees.
std::pair<double, double> cos_sin_deg(double deg) {
    double r = std::fmod(deg, 360.0);
    if (r < 0.0) r += 360.0;
    if (r == 0.0) return {1.0, 0.0};
    if (r == 90.0) return {0.0, 1.0};
    if (r == 180.0) return {-1.0, 0.0};
    if (r == 270.0) return {0.0, -1.0};
    double rad = r * (std::numbers::pi / 180.0);
    return {std::cos(rad), std::sin(rad)};
}

}  // namespace

glm::dmat3 make_rotation(int axis, double deg) {
    auto [c, s] = cos_sin_deg(deg);
    glm::dmat3 m(1.0);  // glm is column-major: m[column][row]
    int a = (axis + 1) % 3;
    int b = (axis + 2) % 3;
    // Right-handed rotation in the (a, b) plane: a -> cos a + sin b, b -> -sin a + cos b.
    m[a][a] = c;
    m[a][b] = s;
    m[b][a] = -s;
    m[b][b] = c;
    return m;
}

glm::dmat3 make_rotation_xyz(glm::dvec3 deg) {
    return make_rotation(2, deg.z) * make_rotation(1, deg.y) * make_rotation(0, deg.x);
}

glm::dmat4 make_world_from_object(const Transform& t) {
    glm::dmat4 m(1.0);
    for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) m[c][r] = t.rotate[c][r] * t.scale[c];
    }
    m[3] = glm::dvec4(t.translate, 1.0);
    return m;
}

glm::dmat4 make_object_from_world(const Transform& t) {
    glm::dmat3 inv_linear = glm::transpose(t.rotate);
    for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) inv_linear[c][r] /= t.scale[r];
    }
    glm::dmat4 m(inv_linear);
    m[3] = glm::dvec4(-(inv_linear * t.translate), 1.0);
    return m;
}

bool is_identity(const Transform& t) {
    return t.translate == glm::dvec3(0.0) && t.rotate == glm::dmat3(1.0) &&
           t.scale == glm::dvec3(1.0);
}

void set_transform(Object& object, const Transform& t) {
    object.has_transform = !is_identity(t);
    object.world_from_object = mat4(make_world_from_object(t));
    object.object_from_world = mat4(make_object_from_world(t));
}

Aabb mesh_bounds(const MeshData& mesh) {
    Aabb box;
    for (vec3 p : mesh.positions) box.grow(p);
    return box;
}

glm::dmat4 make_fit(const Aabb& bounds, double scale, glm::dvec3 offset) {
    glm::dvec3 anchor(0.5 * (double(bounds.lo.x) + double(bounds.hi.x)), double(bounds.lo.y),
                      0.5 * (double(bounds.lo.z) + double(bounds.hi.z)));
    glm::dmat4 m(scale);
    m[3] = glm::dvec4(offset - scale * anchor, 1.0);
    return m;
}

void bake_transform(MeshData& mesh, const glm::dmat4& world_from_object) {
    glm::dmat3 linear(world_from_object);
    glm::dvec3 shift(world_from_object[3]);
    for (vec3& p : mesh.positions) p = vec3(linear * glm::dvec3(p) + shift);

    glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    mesh.normal_to_world = glm::mat3(normal_matrix * glm::dmat3(mesh.normal_to_world));
    for (vec3& n : mesh.normals) {
        glm::dvec3 m = normal_matrix * glm::dvec3(n);
        double len = glm::length(m);
        n = len > 0.0 ? vec3(m / len) : vec3(0.0f);
    }

    if (glm::determinant(linear) < 0.0) {
        for (uvec3& t : mesh.tris) std::swap(t.y, t.z);
        for (uvec3& t : mesh.normal_tris) std::swap(t.y, t.z);
        for (uvec3& t : mesh.uv_tris) std::swap(t.y, t.z);
    }
}

}  // namespace raylane
