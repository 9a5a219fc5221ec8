// Tests of io/model_scene: a model file as a scene of its own, in the model's own units.
#include "io/model_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "scene/transform.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

using test::TempDir;
using test::write_file;

/// An OBJ of the box [lo, hi] scaled by `s` (12 triangles).
std::string box_obj(glm::dvec3 lo, glm::dvec3 hi, double s) {
    std::string obj;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        obj += "v " + std::to_string(s * p.x) + " " + std::to_string(s * p.y) + " " +
               std::to_string(s * p.z) + "\n";
    }
    obj +=
        "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n"
        "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";
    return obj;
}

/// Where a point is seen, in units of the tangent of half the field of view on each axis:
/// inside the frame when both are within [-1, 1].
glm::dvec2 seen_at(const Camera& cam, glm::dvec3 p) {
    const glm::dvec3 eye(cam.position), f = glm::normalize(glm::dvec3(cam.look_at) - eye);
    const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(cam.up)));
    const glm::dvec3 u = glm::cross(r, f), d = p - eye;
    const double tan_v = std::tan(0.5 * double(cam.fov_deg) * 3.14159265358979 / 180.0);
    const double tan_h = tan_v * cam.width / cam.height;
    return {glm::dot(d, r) / glm::dot(d, f) / tan_h, glm::dot(d, u) / glm::dot(d, f) / tan_v};
}

TEST(ModelScene, RecognisesModelsByExtension) {
    EXPECT_TRUE(is_model_file("a/bunny.ply"));
    EXPECT_TRUE(is_model_file("Dragon.OBJ"));
    EXPECT_FALSE(is_model_file("scene.json"));
    EXPECT_FALSE(is_model_file("obj"));
    EXPECT_FALSE(is_model_file("model.ply.txt"));
    EXPECT_TRUE(is_model_file("dragon.obj.GZ"));
    EXPECT_TRUE(is_model_file("bunny.ply.gz"));
    EXPECT_FALSE(is_model_file("notes.gz"));
}

TEST(ModelScene, PutsTheModelOnTheFloorInFrameWithTwoShadowedLights) {
    TempDir dir("raylane_model_scene_");
    write_file(dir.path / "box.obj", box_obj({-3.0, 5.0, 1.0}, {-1.0, 6.0, 4.0}, 1.0));
    const SceneData scene = load_model_scene((dir.path / "box.obj").string());
    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.planes.size(), 1u);
    const Aabb b = mesh_bounds(scene.meshes[0]);
    // the model keeps its size, its bottom on the floor plane
    EXPECT_NEAR(b.extent().x, 2.0f, 1e-5f);
    EXPECT_NEAR(b.extent().y, 1.0f, 1e-5f);
    EXPECT_NEAR(b.extent().z, 3.0f, 1e-5f);
    const float floor_y = glm::dot(scene.planes[0].point, scene.planes[0].normal);
    EXPECT_NEAR(b.lo.y, floor_y, 1e-5f);
    // every corner of its box in the frame, and the box not tiny in it
    double widest = 0.0;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y,
                           i & 4 ? b.hi.z : b.lo.z);
        const glm::dvec2 s = seen_at(scene.camera, p);
        EXPECT_LT(std::fabs(s.x), 1.0) << i;
        EXPECT_LT(std::fabs(s.y), 1.0) << i;
        widest = std::max(widest, std::max(std::fabs(s.x), std::fabs(s.y)));
    }
    EXPECT_GT(widest, 0.4);
    // the camera and both lights above the floor, the lights casting shadows
    EXPECT_GT(scene.camera.position.y, floor_y);
    ASSERT_EQ(scene.lights.size(), 2u);
    for (const Light& l : scene.lights) {
        EXPECT_EQ(l.kind, LightKind::point);
        EXPECT_TRUE(l.shadows);
        EXPECT_GT(l.position.y, b.hi.y);
    }
}

TEST(ModelScene, IsInTheModelsOwnUnits) {
    // the same box in metres and in millimetres: every distance 1000x, the light at the model
    // the same (intensity / d^2)
    TempDir dir("raylane_model_scene_");
    write_file(dir.path / "m.obj", box_obj({0.0, 0.0, 0.0}, {1.0, 2.0, 0.5}, 1.0));
    write_file(dir.path / "mm.obj", box_obj({0.0, 0.0, 0.0}, {1.0, 2.0, 0.5}, 1000.0));
    const SceneData m = load_model_scene((dir.path / "m.obj").string());
    const SceneData mm = load_model_scene((dir.path / "mm.obj").string());
    const glm::dvec3 cm = glm::dvec3(mesh_bounds(m.meshes[0]).center());
    const glm::dvec3 cmm = glm::dvec3(mesh_bounds(mm.meshes[0]).center());
    const double eye_m = glm::length(glm::dvec3(m.camera.position) - cm);
    const double eye_mm = glm::length(glm::dvec3(mm.camera.position) - cmm);
    EXPECT_NEAR(eye_mm / eye_m, 1000.0, 1e-3);
    for (size_t k = 0; k < 2; ++k) {
        const double d_m = glm::length(glm::dvec3(m.lights[k].position) - cm);
        const double d_mm = glm::length(glm::dvec3(mm.lights[k].position) - cmm);
        EXPECT_NEAR(d_mm / d_m, 1000.0, 1e-3);
        EXPECT_NEAR(mm.lights[k].intensity / (d_mm * d_mm), m.lights[k].intensity / (d_m * d_m),
                    1e-5 * m.lights[k].intensity / (d_m * d_m));
    }
}

TEST(ModelScene, TheJsonNamesTheFileAsGivenAndKeepsItsUnits) {
    const std::string json = model_scene_json("dir/my \"model\".obj", Aabb{vec3(0), vec3(1)});
    EXPECT_NE(json.find(R"("file": "dir/my \"model\".obj")"), std::string::npos) << json;
    EXPECT_NE(json.find(R"("fit": {"scale": 1})"), std::string::npos) << json;
}

TEST(ModelScene, AModelWithoutExtentIsRefused) {
    try {
        model_scene_json("point.obj", Aabb{vec3(2.0f), vec3(2.0f)});
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "point.obj: the model has no extent to frame");
    }
    EXPECT_THROW(model_scene_json("empty.obj", Aabb{}), InputError);
}

}  // namespace
}  // namespace raylane
