// tests for scene/builtin_scene.cpp: the built-in scene has every analytic shape and two lights,
// everything in it is in view, and scenes/builtin.json is the same scene.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

#include "io/load_scene.h"
#include "scene/scene.h"

namespace raylane {
namespace {

TEST(BuiltinScene, HasEveryAnalyticShapeKindAndTwoLights) {
    SceneData s = make_builtin_scene();
    EXPECT_EQ(s.source, "<built-in>");
    std::set<ShapeKind> kinds;
    for (const Object& o : s.objects) kinds.insert(o.kind);
    EXPECT_EQ(kinds, (std::set<ShapeKind>{ShapeKind::sphere, ShapeKind::box, ShapeKind::cylinder,
                                          ShapeKind::plane, ShapeKind::triangle}));
    EXPECT_TRUE(s.meshes.empty());
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_NE(s.lights[0].kind, s.lights[1].kind);  // one point, one directional
    for (const Light& l : s.lights) {
        EXPECT_GT(l.intensity, 0.0f);
        if (l.kind == LightKind::directional) {
            EXPECT_NEAR(glm::length(l.direction), 1.0f, 1e-6f);
        }
    }
    EXPECT_EQ(s.camera.width, 640);
    EXPECT_EQ(s.camera.height, 480);
}

TEST(BuiltinScene, ObjectsReferToValidShapesAndDistinctMaterials) {
    SceneData s = make_builtin_scene();
    std::set<std::tuple<float, float, float>> colours;
    for (const Material& m : s.materials) colours.insert({m.c_d.x, m.c_d.y, m.c_d.z});
    EXPECT_EQ(colours.size(), s.materials.size());
    std::set<uint32_t> used;
    for (const Object& o : s.objects) {
        ASSERT_LT(o.material, s.materials.size());
        used.insert(o.material);
        size_t count = 0;
        switch (o.kind) {
            case ShapeKind::sphere:
                count = s.spheres.size();
                break;
            case ShapeKind::box:
                count = s.boxes.size();
                break;
            case ShapeKind::cylinder:
                count = s.cylinders.size();
                break;
            case ShapeKind::plane:
                count = s.planes.size();
                break;
            case ShapeKind::triangle:
                count = s.triangles.size();
                break;
            case ShapeKind::mesh:
                count = s.meshes.size();
                break;
        }
        EXPECT_LT(o.shape, count);
        // object_from_world undoes world_from_object.
        glm::mat4 product = o.object_from_world * o.world_from_object;
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) EXPECT_NEAR(product[c][r], c == r ? 1.0f : 0.0f, 1e-6f);
        }
    }
    EXPECT_EQ(used.size(), s.objects.size()) << "each object has its own material";
}

/// Image position of `p` in [-0.5, 0.5]^2 (x right, y up) for the camera conventions of
/// report-scenes.md 1.1, or a value outside when p is behind the camera.
glm::vec2 project(const Camera& c, vec3 p) {
    vec3 w = glm::normalize(c.look_at - c.position);
    vec3 u = glm::normalize(glm::cross(c.up, w));
    vec3 v = glm::cross(w, u);
    vec3 d = p - c.position;
    float z = glm::dot(d, w);
    if (z <= 0.0f) return glm::vec2(10.0f);
    float t = std::tan(c.fov_deg * float(M_PI) / 360.0f);
    float aspect = float(c.width) / float(c.height);
    float half_w = c.fov_axis == FovAxis::horizontal ? t : t * aspect;
    float half_h = c.fov_axis == FovAxis::horizontal ? t / aspect : t;
    return glm::vec2(glm::dot(d, u) / z / (2.0f * half_w), glm::dot(d, v) / z / (2.0f * half_h));
}

TEST(BuiltinScene, CameraSeesEveryBoundedObject) {
    SceneData s = make_builtin_scene();
    for (const Object& o : s.objects) {
        vec3 centre;
        switch (o.kind) {
            case ShapeKind::sphere:
                centre = s.spheres[o.shape].center;
                break;
            case ShapeKind::box:
                centre = 0.5f * (s.boxes[o.shape].lo + s.boxes[o.shape].hi);
                break;
            case ShapeKind::cylinder:
                centre = vec3(0, 0.5f * s.cylinders[o.shape].height, 0);
                break;
            case ShapeKind::triangle: {
                const Triangle& t = s.triangles[o.shape];
                centre = (t.p0 + t.p1 + t.p2) / 3.0f;
                break;
            }
            default:
                continue;  // the floor plane is unbounded
        }
        vec3 world = vec3(o.world_from_object * glm::vec4(centre, 1.0f));
        glm::vec2 q = project(s.camera, world);
        EXPECT_LT(std::abs(q.x), 0.4f) << "object " << int(o.kind) << " near the left/right edge";
        EXPECT_LT(std::abs(q.y), 0.4f) << "object " << int(o.kind) << " near the top/bottom edge";
    }
}

TEST(BuiltinScene, EqualsScenesBuiltinJson) {
    SceneData a = make_builtin_scene();
    SceneData b = load_scene(RAYLANE_SOURCE_DIR "/scenes/builtin.json");
    EXPECT_EQ(a.camera.position, b.camera.position);
    EXPECT_EQ(a.camera.look_at, b.camera.look_at);
    EXPECT_EQ(a.camera.up, b.camera.up);
    EXPECT_EQ(a.camera.fov_deg, b.camera.fov_deg);
    EXPECT_EQ(a.camera.fov_axis, b.camera.fov_axis);
    EXPECT_EQ(a.camera.width, b.camera.width);
    EXPECT_EQ(a.camera.height, b.camera.height);
    EXPECT_EQ(a.camera.spp, b.camera.spp);
    EXPECT_EQ(a.background, b.background);
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) {
        EXPECT_EQ(a.materials[i].name, b.materials[i].name);
        EXPECT_EQ(a.materials[i].c_d, b.materials[i].c_d);
        EXPECT_EQ(a.materials[i].k_d, b.materials[i].k_d);
        EXPECT_EQ(a.materials[i].k_a, b.materials[i].k_a);
        EXPECT_EQ(a.materials[i].c_s, b.materials[i].c_s);
        EXPECT_EQ(a.materials[i].k_s, b.materials[i].k_s);
        EXPECT_EQ(a.materials[i].exponent, b.materials[i].exponent);
    }
    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (size_t i = 0; i < a.lights.size(); ++i) {
        EXPECT_EQ(a.lights[i].kind, b.lights[i].kind);
        EXPECT_EQ(a.lights[i].position, b.lights[i].position);
        EXPECT_EQ(a.lights[i].direction, b.lights[i].direction);
        EXPECT_EQ(a.lights[i].color, b.lights[i].color);
        EXPECT_EQ(a.lights[i].intensity, b.lights[i].intensity);
        EXPECT_EQ(a.lights[i].shadows, b.lights[i].shadows);
    }
    ASSERT_EQ(a.objects.size(), b.objects.size());
    for (size_t i = 0; i < a.objects.size(); ++i) {
        EXPECT_EQ(a.objects[i].kind, b.objects[i].kind);
        EXPECT_EQ(a.objects[i].shape, b.objects[i].shape);
        EXPECT_EQ(a.objects[i].material, b.objects[i].material);
        EXPECT_EQ(a.objects[i].has_transform, b.objects[i].has_transform);
        EXPECT_EQ(a.objects[i].world_from_object, b.objects[i].world_from_object);
        EXPECT_EQ(a.objects[i].object_from_world, b.objects[i].object_from_world);
    }
    ASSERT_EQ(a.spheres.size(), b.spheres.size());
    for (size_t i = 0; i < a.spheres.size(); ++i) {
        EXPECT_EQ(a.spheres[i].center, b.spheres[i].center);
        EXPECT_EQ(a.spheres[i].radius, b.spheres[i].radius);
    }
    ASSERT_EQ(a.boxes.size(), b.boxes.size());
    for (size_t i = 0; i < a.boxes.size(); ++i) {
        EXPECT_EQ(a.boxes[i].lo, b.boxes[i].lo);
        EXPECT_EQ(a.boxes[i].hi, b.boxes[i].hi);
    }
    ASSERT_EQ(a.cylinders.size(), b.cylinders.size());
    for (size_t i = 0; i < a.cylinders.size(); ++i) {
        EXPECT_EQ(a.cylinders[i].radius, b.cylinders[i].radius);
        EXPECT_EQ(a.cylinders[i].height, b.cylinders[i].height);
    }
    ASSERT_EQ(a.planes.size(), b.planes.size());
    for (size_t i = 0; i < a.planes.size(); ++i) {
        EXPECT_EQ(a.planes[i].point, b.planes[i].point);
        EXPECT_EQ(a.planes[i].normal, b.planes[i].normal);
    }
    ASSERT_EQ(a.triangles.size(), b.triangles.size());
    for (size_t i = 0; i < a.triangles.size(); ++i) {
        EXPECT_EQ(a.triangles[i].p0, b.triangles[i].p0);
        EXPECT_EQ(a.triangles[i].p1, b.triangles[i].p1);
        EXPECT_EQ(a.triangles[i].p2, b.triangles[i].p2);
    }
    EXPECT_EQ(a.meshes.size(), b.meshes.size());
}

TEST(CountTriangles, SumsMeshTrianglesAndSingleTriangles) {
    SceneData s;
    EXPECT_EQ(count_triangles(s), 0u);
    s.triangles.resize(2);
    MeshData m;
    m.tris.resize(5);
    s.meshes.push_back(m);
    m.tris.resize(7);
    s.meshes.push_back(m);
    EXPECT_EQ(count_triangles(s), 14u);
}

}  // namespace
}  // namespace raylane
