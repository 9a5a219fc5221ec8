// Tests of render/render_scalar.cpp: determinism, sampling, AOVs and shading on small scenes.
#include "render/render_scalar.h"

#include <gtest/gtest.h>

namespace raylane {
namespace {

SceneData small_builtin(int w, int h) {
    SceneData scene = make_builtin_scene();
    scene.camera.width = w;
    scene.camera.height = h;
    return scene;
}

/// One diffuse sphere of radius 1 at z = 3, a directional light along the view axis.
SceneData lit_sphere() {
    SceneData scene;
    scene.camera.width = 33;
    scene.camera.height = 33;
    scene.camera.fov_deg = 60.0f;
    Material white;
    white.name = "white";
    white.c_d = vec3(1.0f);
    white.k_d = 1.0f;
    white.k_s = 0.0f;
    scene.materials.push_back(white);
    scene.spheres.push_back({vec3(0.0f, 0.0f, 3.0f), 1.0f});
    scene.objects.push_back({ShapeKind::sphere, 0, 0});
    Light light;
    light.kind = LightKind::directional;
    light.direction = vec3(0.0f, 0.0f, -1.0f);
    light.intensity = 0.5f;
    scene.lights.push_back(light);
    return scene;
}

TEST(RenderScalar, SameImageForOneAndTwoThreads) {
    const SceneData scene = small_builtin(96, 64);
    const Accel accel = build_accel(scene, BuildParams{});
    RenderParams p;
    p.spp = 3;
    p.tile_size = 8;
    p.threads = 1;
    const RenderResult one = render_scalar(scene, accel, p);
    p.threads = 2;
    const RenderResult two = render_scalar(scene, accel, p);
    ASSERT_EQ(one.film.pixels.size(), two.film.pixels.size());
    for (size_t i = 0; i < one.film.pixels.size(); ++i)
        ASSERT_EQ(one.film.pixels[i], two.film.pixels[i]) << "pixel " << i;
    EXPECT_EQ(one.stats.shadow_rays, two.stats.shadow_rays);
}

TEST(RenderScalar, BuiltinSceneIsNotBlankAndShowsSeveralColours) {
    const SceneData scene = small_builtin(64, 48);
    const RenderResult r = render_scalar(scene, build_accel(scene, BuildParams{}), RenderParams{});
    int lit = 0;
    vec3 lo(1e9f), hi(-1e9f);
    for (const vec3& p : r.film.pixels) {
        lit += (p.x + p.y + p.z) > 0.05f;
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    EXPECT_GT(lit, 64 * 48 / 4);
    EXPECT_GT(hi.x - lo.x, 0.2f);
    EXPECT_GT(r.stats.shadow_rays, 0u);
    EXPECT_EQ(r.stats.primary_rays, 64u * 48u);
}

TEST(RenderScalar, DiffuseSphereCentreMatchesTheReportsEquation) {
    // centre pixel: normal faces the light, cos = 1: L = k_d * intensity * c_d = 0.5
    const SceneData scene = lit_sphere();
    const RenderResult r = render_scalar(scene, build_accel(scene, BuildParams{}), RenderParams{});
    EXPECT_NEAR(r.film.at(16, 16).x, 0.5f, 1e-4f);
    EXPECT_EQ(r.film.at(0, 0), vec3(0.0f));  // background
    // off-centre pixels are darker by cos(theta)
    EXPECT_LT(r.film.at(16, 10).x, r.film.at(16, 16).x);
}

TEST(RenderScalar, ShadowRaysDarkenOccludedPoints) {
    SceneData scene = lit_sphere();
    // a big occluder between the light (at -z, towards the camera) and the sphere... place a
    // point light behind the camera and a small sphere that shadows the centre.
    scene.lights[0].kind = LightKind::point;
    scene.lights[0].position = vec3(0.0f, 0.0f, -5.0f);
    scene.lights[0].intensity = 10.0f;
    scene.spheres.push_back({vec3(0.0f, 0.0f, -2.0f), 0.1f});  // behind the camera, on the axis
    scene.objects.push_back({ShapeKind::sphere, 1, 0});
    const Accel accel = build_accel(scene, BuildParams{});
    RenderResult r = render_scalar(scene, accel, RenderParams{});
    EXPECT_EQ(r.film.at(16, 16), vec3(0.0f));  // in the small sphere's shadow
    EXPECT_GT(r.film.at(16, 12).x, 0.0f);      // outside it
    scene.lights[0].shadows = false;
    r = render_scalar(scene, accel, RenderParams{});
    EXPECT_GT(r.film.at(16, 16).x, 0.0f);
}

TEST(RenderScalar, JitteredSamplesChangeWithTheSeedOnly) {
    const SceneData scene = small_builtin(32, 24);
    const Accel accel = build_accel(scene, BuildParams{});
    RenderParams p;
    p.spp = 4;
    const RenderResult a = render_scalar(scene, accel, p);
    const RenderResult b = render_scalar(scene, accel, p);
    p.seed = 1;
    const RenderResult c = render_scalar(scene, accel, p);
    EXPECT_EQ(a.film.pixels, b.film.pixels);
    EXPECT_NE(a.film.pixels, c.film.pixels);
}

TEST(RenderScalar, AovsHaveTheirMeaning) {
    const SceneData scene = lit_sphere();
    const Accel accel = build_accel(scene, BuildParams{});
    RenderParams p;
    p.aov = Aov::depth;
    EXPECT_NEAR(render_scalar(scene, accel, p).film.at(16, 16).x, 2.0f, 1e-4f);
    p.aov = Aov::normal;
    EXPECT_NEAR(render_scalar(scene, accel, p).film.at(16, 16).z, -1.0f, 1e-4f);
    p.aov = Aov::bvh_cost;
    const RenderResult cost = render_scalar(scene, accel, p);
    EXPECT_GE(cost.film.at(16, 16).x, 1.0f);
}

}  // namespace
}  // namespace raylane
