// Tests of report/warnings: one line for each scene or render that will not show what was meant.
#include "report/warnings.h"

#include <gtest/gtest.h>

#include <string>

#include "support/geometry_support.h"

namespace raylane {
namespace {

SceneData one_sphere_scene(vec3 look_at, bool lit) {
    SceneData s;
    s.materials.push_back(Material{});
    s.spheres.push_back(Sphere{vec3(0.0f), 1.0f});
    Object o;
    o.kind = ShapeKind::sphere;
    s.objects.push_back(o);
    s.camera.position = vec3(0.0f, 0.0f, -5.0f);
    s.camera.look_at = look_at;
    if (lit) s.lights.push_back(Light{});
    return s;
}

TEST(Warnings, AWellSetSceneHasNone) {
    const SceneData s = one_sphere_scene(vec3(0.0f), true);
    EXPECT_TRUE(scene_warnings(s, build_accel(s, BuildParams{})).empty());
}

TEST(Warnings, NoLightsAndACameraThatSeesNothing) {
    const SceneData s = one_sphere_scene(vec3(0.0f, 0.0f, -10.0f), false);
    const std::vector<std::string> w = scene_warnings(s, build_accel(s, BuildParams{}));
    ASSERT_EQ(w.size(), 2u);
    EXPECT_EQ(w[0].rfind("the scene has no lights", 0), 0u) << w[0];
    EXPECT_EQ(w[1], "the camera sees no object: check its position, look_at and fov_deg");
}

TEST(Warnings, ASceneWithoutObjects) {
    SceneData s;
    s.lights.push_back(Light{});
    const std::vector<std::string> w = scene_warnings(s, build_accel(s, BuildParams{}));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0], "the scene has no objects: the image is the background");
}

TEST(Warnings, ABlackImageAndAllNanSamples) {
    Film film = make_film(4, 2);
    RenderStats stats;
    EXPECT_EQ(render_warnings(film, stats, 8), std::vector<std::string>{"every pixel is black"});
    stats.nan_samples = 8;
    EXPECT_EQ(render_warnings(film, stats, 8),
              std::vector<std::string>{"every sample was NaN: the image is black"});
    stats.nan_samples = 7;
    film.at(3, 1) = vec3(0.0f, 1e-30f, 0.0f);
    EXPECT_TRUE(render_warnings(film, stats, 8).empty());
}

}  // namespace
}  // namespace raylane
