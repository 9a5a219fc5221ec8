// tests for the shading features in both renderers: the kernels compiled for a scene's features
// give the generic kernel's image, and the optical terms do what the report says they do.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "io/load_scene.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "report/compare.h"
#include "support/small_scene.h"

namespace raylane {
namespace {

using namespace test;

SceneData scene_file(const std::string& name) {
    return load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name);
}

/// Every scene of scenes/: the kernel specialised to the scene's features renders exactly the
/// image of the all-features kernel (the features left out really are unused; scenes without
/// secondary rays take the one-pass path, shade_camera_block).
TEST(RenderFeatures, SpecialisedKernelsGiveTheGenericKernelsImage) {
    int scenes = 0;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(RAYLANE_SOURCE_DIR) + "/scenes")) {
        if (entry.path().extension() != ".json") continue;
        SceneData scene;
        try {
            scene = load_scene(entry.path().string());
        } catch (const std::exception& e) {
            EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
            continue;
        }
        // 50 wide and an odd height: packets (4x4 at W = 16) partial at the right and bottom edges
        scene = small_scene(scene, 50);
        scene.camera.height = scene.camera.height / 2 * 2 + 1;
        const Accel accel = build_accel(scene, BuildParams{});
        RenderParams p;
        p.spp = 1;
        p.light_samples = 2;
        p.glossy_samples = 2;
        const RenderResult specialised = render_packet(scene, accel, p);
        p.generic_kernel = true;
        const RenderResult generic = render_packet(scene, accel, p);
        EXPECT_EQ(diff_images(specialised.film, generic.film).max_abs, 0.0) << entry.path();
        EXPECT_EQ(specialised.stats.total_rays(), generic.stats.total_rays()) << entry.path();
        ++scenes;
    }
    EXPECT_GE(scenes, 20);
}

/// Glass of index 1 that absorbs nothing is invisible: the image equals the environment alone.
TEST(RenderFeatures, GlassOfIndexOneIsInvisible) {
    SceneData scene = small_scene(scene_file("fig05_refractive_sphere.json"), 64);
    scene.materials[0].ior = 1.0f;
    SceneData empty = scene;
    empty.objects.clear();
    for (auto* render : {&render_scalar, &render_packet}) {
        const Accel accel = build_accel(scene, BuildParams{});
        const Accel accel_empty = build_accel(empty, BuildParams{});
        const RenderResult with = (*render)(scene, accel, RenderParams{});
        const RenderResult without = (*render)(empty, accel_empty, RenderParams{});
        EXPECT_GT(with.stats.refraction_rays, 0u);
        // R = 0 exactly at eta = 1, so nothing is reflected; the ray goes straight through
        EXPECT_LT(diff_images(with.film, without.film).max_abs, 1e-6);
    }
}

/// Figure 4c: with the reflected radiance replaced by magenta and the local term off, the
/// sphere's centre shows R c_s magenta with R = Schlick(0.5, 1) = 0.5.
TEST(RenderFeatures, ReflectedColourOverrideShowsTheFresnelWeight) {
    SceneData scene = small_scene(scene_file("fig04c_reflection_magenta.json"), 65);
    scene.shading.local = false;
    scene.materials[0].k_a_after = 0.0f;
    const Accel accel = build_accel(scene, BuildParams{});
    for (auto* render : {&render_scalar, &render_packet}) {
        const RenderResult r = (*render)(scene, accel, RenderParams{});
        const vec3 centre = r.film.at(32, 32);
        EXPECT_NEAR(centre.x, 0.5f, 2e-3);
        EXPECT_NEAR(centre.y, 0.0f, 1e-6);
        EXPECT_NEAR(centre.z, 0.5f, 2e-3);
        // towards the rim the weight grows towards 1 (Schlick)
        EXPECT_GT(r.film.at(32, 2).x, centre.x);
        EXPECT_EQ(r.stats.reflection_rays, 0u);  // nothing is traced for the override
    }
}

/// A lens of radius 0 is the pinhole camera; a real lens blurs what is off the plane of focus
/// and keeps what is on it.
TEST(RenderFeatures, ThinLensFocusesOnItsPlane) {
    SceneData scene = small_scene(scene_file("fig08a_dof_close.json"), 64);
    const Accel accel = build_accel(scene, BuildParams{});
    RenderParams p;
    p.spp = 16;
    SceneData pinhole = scene;
    pinhole.camera.lens_radius = 0.0f;
    const RenderResult sharp = render_packet(pinhole, accel, p);
    const RenderResult lens = render_packet(scene, accel, p);
    const RenderResult lens_scalar = render_scalar(scene, accel, p);
    EXPECT_LT(diff_images(lens.film, lens_scalar.film).max_abs, 1e-5);
    EXPECT_GT(diff_images(sharp.film, lens.film).max_abs, 0.05);
    // the blue sphere at depth 9 is in focus: its centre pixel changes little
    // (its centre projects to x = 0.5 + 0.5 * (-5 / 9) / tan(30 deg) of the width)
    const int x = int(64 * (0.5 - 0.5 * (5.0 / 9.0) / std::tan(std::numbers::pi / 6)));
    const int y = int(64 * (0.5 + 0.5 * (2.0 / 9.0) / std::tan(std::numbers::pi / 6)));
    const vec3 a = sharp.film.at(x, y), b = lens.film.at(x, y);
    EXPECT_LT(std::abs(a.z - b.z), 0.1f) << a.z << " " << b.z;
}

}  // namespace
}  // namespace raylane
