// scene: the plain data every stage reads. Loaded by io/load_scene.cpp or made by
// scene/builtin_scene.cpp; the BVHs over it live in accel/ (Accel).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/ray.h"

namespace raylane {

using glm::mat4;
using glm::uvec3;

/// Which image-plane extent the field of view spans.
enum class FovAxis : uint8_t { vertical, horizontal };

struct Camera {
    vec3 position{0.0f, 0.0f, 0.0f};
    vec3 look_at{0.0f, 0.0f, 1.0f};
    vec3 up{0.0f, 1.0f, 0.0f};
    float fov_deg = 60.0f;
    FovAxis fov_axis = FovAxis::vertical;
    int width = 640;
    int height = 480;
    int spp = 1;  ///< samples per pixel; 1 = pixel centre, more = jittered
};

/// The report's local material: L = k_a c_d + sum over lights of
/// k_d c_light F c_d cos(theta) + k_s c_light F c_s cos^e(alpha).
struct Material {
    std::string name;
    vec3 c_d{0.8f};
    float k_d = 1.0f;
    float k_a = 0.0f;
    vec3 c_s{1.0f};
    float k_s = 0.0f;
    float exponent = 32.0f;
};

enum class LightKind : uint8_t { point, directional };

/// Point light: factor intensity / d^2 at distance d. Directional: factor intensity,
/// `direction` points from the scene towards the light (unit length).
struct Light {
    LightKind kind = LightKind::point;
    vec3 position{0.0f};
    vec3 direction{0.0f, 1.0f, 0.0f};
    vec3 color{1.0f};
    float intensity = 1.0f;
    bool shadows = true;
};

// Shapes in object space. Each object refers to one by (kind, index).
struct Sphere {
    vec3 center{0.0f};
    float radius = 1.0f;
};
struct Box {
    vec3 lo{-1.0f};
    vec3 hi{1.0f};
};
/// Finite cylinder around +y from y = 0 to y = height, with caps (the report's convention).
struct Cylinder {
    float radius = 1.0f;
    float height = 1.0f;
};
/// Infinite plane through `point` with unit `normal`. Planes live outside the BVH.
struct Plane {
    vec3 point{0.0f};
    vec3 normal{0.0f, 1.0f, 0.0f};
};
struct Triangle {
    vec3 p0{0.0f}, p1{1.0f, 0.0f, 0.0f}, p2{0.0f, 1.0f, 0.0f};
};

/// A triangle mesh in world space (object transforms are applied at load).
/// Positions, normals and uvs have their own index triples, as in OBJ; normal_tris and uv_tris
/// are empty when the mesh has no normals or uvs, else they have one entry per triangle.
struct Mesh {
    std::string name;
    std::vector<vec3> positions;
    std::vector<vec3> normals;
    std::vector<vec2> uvs;
    std::vector<uvec3> tris;
    std::vector<uvec3> normal_tris;
    std::vector<uvec3> uv_tris;
    size_t triangle_count() const { return tris.size(); }
};

enum class ShapeKind : uint8_t { sphere, box, cylinder, plane, triangle, mesh };

/// Object = shape + material + transform. Analytic shapes are intersected in object space
/// (the ray is moved there by object_from_world); meshes are already in world space.
struct Object {
    ShapeKind kind = ShapeKind::sphere;
    uint32_t shape = 0;     ///< index into the Scene array of that kind
    uint32_t material = 0;  ///< index into Scene::materials
    bool has_transform = false;
    mat4 world_from_object{1.0f};
    mat4 object_from_world{1.0f};
};

struct Scene {
    std::string source;  ///< file the scene came from ("<built-in>" otherwise)
    Camera camera;
    vec3 background{0.0f};
    std::vector<Material> materials;
    std::vector<Light> lights;
    std::vector<Object> objects;
    std::vector<Sphere> spheres;
    std::vector<Box> boxes;
    std::vector<Cylinder> cylinders;
    std::vector<Plane> planes;
    std::vector<Triangle> triangles;
    std::vector<Mesh> meshes;
};

/// The scene that needs no model file: sphere, box, cylinder, plane and a triangle, two lights.
Scene make_builtin_scene();

/// Number of triangles over all meshes and single triangles.
size_t count_triangles(const Scene& scene);

}  // namespace raylane
