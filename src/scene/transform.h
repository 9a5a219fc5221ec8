// scene: object transforms - world_from_object from translate / rotate / scale, the mesh "fit"
// normalisation, and baking a transform into a MeshData. Used by io/load_scene_objects.cpp and
// builtin_scene.cpp.
#pragma once

#include <glm/glm.hpp>

#include "core/aabb.h"
#include "scene/scene.h"

namespace raylane {

/// Rotation by `deg` degrees about axis 0 (x), 1 (y) or 2 (z), right-handed: a positive angle
/// about y maps +x towards -z (report-scenes.md, notation). Multiples of 90 degrees are exact.
glm::dmat3 make_rotation(int axis, double deg);

/// Rx(deg.x), then Ry(deg.y), then Rz(deg.z): the matrix Rz * Ry * Rx.
glm::dmat3 make_rotation_xyz(glm::dvec3 deg);

/// An affine transform given by its parts, in double precision.
/// world_from_object = T(translate) * rotate * S(scale): scale first, then rotate, then translate.
struct Transform {
    glm::dvec3 translate{0.0};
    glm::dmat3 rotate{1.0};  ///< orthonormal, determinant +1
    glm::dvec3 scale{1.0};   ///< every component non-zero (negative mirrors)
};

/// T(translate) * rotate * S(scale).
glm::dmat4 make_world_from_object(const Transform& t);

/// The exact inverse S(1 / scale) * transpose(rotate) * T(-translate).
glm::dmat4 make_object_from_world(const Transform& t);

/// True when the transform is exactly the identity.
bool is_identity(const Transform& t);

/// Stores the transform on an analytic object: both matrices (rounded to float once) and
/// has_transform = !is_identity(t).
void set_transform(Object& object, const Transform& t);

/// Bounding box of the mesh's positions (empty for a mesh without positions).
Aabb mesh_bounds(const MeshData& mesh);

/// The scene format's "fit": moves the bottom centre of `bounds` (centre in x and z, lowest
/// point in y) to the origin, scales uniformly by `scale`, then translates by `offset`.
glm::dmat4 make_fit(const Aabb& bounds, double scale, glm::dvec3 offset);

/// Applies `world_from_object` to the mesh in place: positions by the matrix, normals by the
/// inverse transpose of its linear part, renormalised (a zero normal stays zero). When the
/// linear part has a negative determinant (a mirror) each triangle's winding is reversed, in
/// tris, normal_tris and uv_tris alike, so the winding keeps facing the way the normals do.
void bake_transform(MeshData& mesh, const glm::dmat4& world_from_object);

}  // namespace raylane
