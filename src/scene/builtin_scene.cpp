// scene: the scene that needs no model file (scene.h). scenes/builtin.json is the same scene
// written in the scene format; tests/scene/builtin_scene_test.cpp checks that the two agree.
#include <glm/glm.hpp>
#include <utility>

#include "scene/scene.h"
#include "scene/transform.h"

namespace raylane {

namespace {

Material make_phong(std::string name, vec3 c_d, float k_d, float k_s, float exponent) {
    Material m;
    m.name = std::move(name);
    m.c_d = c_d;
    m.k_d = k_d;
    m.k_a = 0.1f;
    m.c_s = vec3(1.0f);
    m.k_s = k_s;
    m.exponent = exponent;
    return m;
}

/// Normalised in double, as the loader normalises directions.
vec3 unit(glm::dvec3 v) { return vec3(v / glm::length(v)); }

void add_object(SceneData& scene, ShapeKind kind, uint32_t shape, uint32_t material,
                const Transform& t = {}) {
    Object o;
    o.kind = kind;
    o.shape = shape;
    o.material = material;
    set_transform(o, t);
    scene.objects.push_back(o);
}

}  // namespace

SceneData make_builtin_scene() {
    SceneData scene;
    scene.source = "<built-in>";

    scene.camera.position = vec3(0.0f, 2.5f, -7.0f);
    scene.camera.look_at = vec3(0.0f, 0.9f, 0.5f);
    scene.camera.up = vec3(0.0f, 1.0f, 0.0f);
    scene.camera.fov_deg = 50.0f;
    scene.camera.fov_axis = FovAxis::vertical;
    scene.camera.width = 640;
    scene.camera.height = 480;
    scene.camera.spp = 4;
    scene.background = vec3(0.05f, 0.07f, 0.1f);

    // Materials, in the order of scenes/builtin.json.
    scene.materials.push_back(make_phong("floor", vec3(0.7f, 0.7f, 0.65f), 0.6f, 0.1f, 20.0f));
    scene.materials.push_back(make_phong("red", vec3(0.85f, 0.15f, 0.1f), 0.7f, 0.5f, 60.0f));
    scene.materials.push_back(make_phong("blue", vec3(0.15f, 0.35f, 0.85f), 0.7f, 0.3f, 30.0f));
    scene.materials.push_back(make_phong("green", vec3(0.2f, 0.7f, 0.3f), 0.7f, 0.4f, 40.0f));
    scene.materials.push_back(make_phong("gold", vec3(0.95f, 0.7f, 0.15f), 0.6f, 0.3f, 50.0f));

    // Floor: the plane y = 0.
    scene.planes.push_back(Plane{vec3(0.0f), vec3(0.0f, 1.0f, 0.0f)});
    add_object(scene, ShapeKind::plane, 0, 0);

    // A red sphere resting on the floor, left.
    scene.spheres.push_back(Sphere{vec3(-1.8f, 1.0f, 0.8f), 1.0f});
    add_object(scene, ShapeKind::sphere, 0, 1);

    // A blue cube turned 35 degrees about y, in the middle and in front.
    scene.boxes.push_back(Box{vec3(-0.6f, 0.0f, -0.6f), vec3(0.6f, 1.2f, 0.6f)});
    Transform box_transform;
    box_transform.translate = glm::dvec3(0.2, 0.0, -0.9);
    box_transform.rotate = make_rotation(1, 35.0);
    add_object(scene, ShapeKind::box, 0, 2, box_transform);

    // A green cylinder standing on the floor, right.
    scene.cylinders.push_back(Cylinder{0.5f, 1.8f});
    Transform cylinder_transform;
    cylinder_transform.translate = glm::dvec3(1.9, 0.0, 0.9);
    add_object(scene, ShapeKind::cylinder, 0, 3, cylinder_transform);

    // A gold triangle standing behind them, facing the camera.
    scene.triangles.push_back(
        Triangle{vec3(-3.5f, 0.0f, 3.5f), vec3(3.5f, 0.0f, 3.5f), vec3(0.0f, 3.8f, 3.5f)});
    add_object(scene, ShapeKind::triangle, 0, 4);

    // A warm point light above left, in front; a cool directional light from the right.
    Light key;
    key.kind = LightKind::point;
    key.position = vec3(-3.5f, 6.0f, -3.0f);
    key.color = vec3(1.0f, 0.92f, 0.8f);
    key.intensity = 45.0f;
    key.shadows = true;
    scene.lights.push_back(key);

    Light fill;
    fill.kind = LightKind::directional;
    fill.direction = unit(glm::dvec3(1.0, 1.5, -1.0));
    fill.color = vec3(0.6f, 0.7f, 1.0f);
    fill.intensity = 0.35f;
    fill.shadows = true;
    scene.lights.push_back(fill);

    return scene;
}

size_t count_triangles(const SceneData& scene) {
    size_t n = scene.triangles.size();
    for (const MeshData& mesh : scene.meshes) n += mesh.triangle_count();
    return n;
}

}  // namespace raylane
