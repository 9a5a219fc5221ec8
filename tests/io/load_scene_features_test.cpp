// tests for io/load_scene.cpp, the keys of the shading features: materials (lobes, presets,
// mirrors, glass, textures, maps, emission), area lights and their visible stand-ins, the thin
// lens, environment, shading options and tone mapping; and scene/features.h on the result.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/error.h"
#include "io/load_scene.h"
#include "scene/features.h"

namespace raylane {
namespace {

const char* const features_camera =
    R"("camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60})";

SceneData load_members(const std::string& members) {
    return load_scene_from_string(std::string("{") + features_camera + ", " + members + "}",
                                  std::string(RAYLANE_SOURCE_DIR) + "/scenes/test.json");
}

std::string members_error(const std::string& members) {
    try {
        load_members(members);
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        return message;
    }
    ADD_FAILURE() << "no InputError for: " << members;
    return "";
}

TEST(LoadSceneFeatures, ReadsMirrorAndGlassMaterials) {
    const SceneData s = load_members(R"("materials": {
        "m": {"reflection": 0.5, "k_a_after": 1, "fresnel": false},
        "g": {"refraction": {"ior": 1.33, "filter": [1, 0.9, 0.8]}}})");
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_FLOAT_EQ(s.materials[0].reflection, 0.5f);
    EXPECT_FLOAT_EQ(s.materials[0].k_a_after, 1.0f);
    EXPECT_FALSE(s.materials[0].fresnel);
    EXPECT_FALSE(s.materials[0].refractive);
    EXPECT_TRUE(s.materials[1].refractive);
    EXPECT_FLOAT_EQ(s.materials[1].ior, 1.33f);
    EXPECT_FLOAT_EQ(s.materials[1].filter.z, 0.8f);
}

TEST(LoadSceneFeatures, PresetsSetTheFittedParametersOfTheModel) {
    const SceneData s = load_members(R"("materials": {"n": {"model": "ward", "preset": "nickel"},
                                          "d": {"model": "blinn-phong", "preset": "delrin"}})");
    EXPECT_EQ(s.materials[0].model, SpecularModel::ward);
    EXPECT_FLOAT_EQ(s.materials[0].alpha, 0.0432f);
    EXPECT_FLOAT_EQ(s.materials[0].c_s.x, 0.204f);
    EXPECT_EQ(s.materials[1].model, SpecularModel::blinn_phong);
    EXPECT_FLOAT_EQ(s.materials[1].exponent, 83.4f);
    EXPECT_NE(members_error(R"("materials": {"p": {"model": "phong", "preset": "nickel"}})")
                  .find("$.materials.p.preset: no fitted"),
              std::string::npos);
    EXPECT_NE(
        members_error(R"("materials": {"p": {"model": "ward", "preset": "gold"}})").find("gold"),
        std::string::npos);
}

TEST(LoadSceneFeatures, AreaLightsAddAVisibleEmitterThatCastsNoShadow) {
    const SceneData s = load_members(R"("lights": [
        {"type": "box", "min": [-3, 5.5, 11], "max": [-2, 9.5, 11], "intensity": 400,
         "samples": 25},
        {"type": "rect", "corner": [0, 2, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 2],
         "intensity": 10},
        {"type": "disk", "center": [0, 3, 0], "normal": [0, -1, 0], "radius": 0.5,
         "visible": false}])");
    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_EQ(s.lights[0].kind, LightKind::box);
    EXPECT_EQ(s.lights[0].samples, 25);
    EXPECT_EQ(s.lights[1].samples, 16);  // the default
    // the box: one object; the rectangle: two triangles; the invisible disc: nothing
    ASSERT_EQ(s.objects.size(), 3u);
    for (const Object& o : s.objects) EXPECT_FALSE(o.casts_shadows);
    // the report's rule: emission = I / (4 pi 2ab), a = 1 and b = 4 for the 1 x 4 x 0 box
    const Material& box = s.materials[s.objects[0].material];
    EXPECT_NEAR(box.emission.x, 400.0 / (4.0 * std::numbers::pi * 8.0), 1e-5);
    EXPECT_TRUE(box.emissive());
    const Material& rect = s.materials[s.objects[1].material];
    EXPECT_NEAR(rect.emission.y, 10.0 / (4.0 * std::numbers::pi * 4.0), 1e-6);
    EXPECT_NE(members_error(R"("lights": [{"type": "rect", "corner": [0, 0, 0], "edge_u": [1, 0, 0],
                                     "edge_v": [2, 0, 0]}])")
                  .find("$.lights[0].edge_v: the rectangle has zero area"),
              std::string::npos);
    EXPECT_NE(members_error(R"("lights": [{"type": "point", "position": [0, 0, 0], "samples": 4}])")
                  .find("$.lights[0].samples: unknown key"),
              std::string::npos);
}

TEST(LoadSceneFeatures, ReadsTheLensTheShadingOptionsAndTheTonemap) {
    const SceneData s = load_members(R"("shading": {"brdf": "report", "max_reflection_depth": 50,
                                         "local": false, "reflected_color": [1, 0, 1]},
                            "tonemap": "report")");
    EXPECT_EQ(s.shading.brdf, BrdfScaling::report);
    EXPECT_EQ(s.shading.max_reflection_depth, 50);
    EXPECT_FALSE(s.shading.local);
    EXPECT_TRUE(s.shading.override_reflected);
    EXPECT_EQ(s.shading.reflected_color, vec3(1.0f, 0.0f, 1.0f));
    EXPECT_EQ(s.tonemap, Tonemap::report);
    // focal distance defaults to the look-at distance
    const SceneData lens = load_scene_from_string(
        R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 7], "fov_deg": 60,
                       "lens_radius": 0.25}})",
        "lens.json");
    EXPECT_FLOAT_EQ(lens.camera.lens_radius, 0.25f);
    EXPECT_FLOAT_EQ(lens.camera.focal_distance, 7.0f);
    EXPECT_NE(members_error(R"("shading": {"max_reflection_depth": 1000})")
                  .find("$.shading.max_reflection_depth: must be an integer from 0 to 64"),
              std::string::npos);
}

TEST(LoadSceneFeatures, TexturesAreLoadedOnceAndMissingOnesNameWhereItLooked) {
    const SceneData s = load_members(R"("environment": {"file": "envMap2.jpg", "filter": "nearest"},
        "materials": {"a": {"texture": "apple_texture.jpg", "texture_specular": true},
                      "b": {"texture": "apple_texture.jpg"},
                      "c": {"texture": {"checker": [[1, 1, 1], [0, 0, 0]], "checks": 4}}})");
    ASSERT_EQ(s.textures.size(), 3u);  // envMap2, the apple texture once, the checker
    EXPECT_EQ(s.materials[0].texture, s.materials[1].texture);
    EXPECT_EQ(s.textures[size_t(s.environment)].filter, TextureFilter::nearest);
    EXPECT_EQ(s.textures[size_t(s.materials[2].texture)].kind, TextureKind::checker);
    const std::string e = members_error(R"("materials": {"a": {"texture": "no_such.png"}})");
    EXPECT_NE(e.find("$.materials.a.texture: no_such.png: image not found; looked in"),
              std::string::npos)
        << e;
}

TEST(LoadSceneFeatures, FeaturesListWhatTheSceneUses) {
    const SceneData plain = load_members(R"("materials": {"m": {}},
        "objects": [{"shape": "sphere", "radius": 1, "material": "m"}],
        "lights": [{"type": "point", "position": [0, 5, 0]}])");
    const uint32_t f = scene_features(plain);
    EXPECT_EQ(f & kernel_features_all, 0u);
    EXPECT_NE(f & feature_point_lights, 0u);
    EXPECT_NE(f & feature_analytic_shapes, 0u);
    const SceneData rich = load_members(R"("materials": {"g": {"refraction": {}},
                                             "s": {"model": "glossy-phong"}},
        "lights": [{"type": "disk", "center": [0, 3, 0], "normal": [0, -1, 0], "radius": 1}])");
    const uint32_t r = scene_features(rich);
    EXPECT_NE(r & feature_refraction, 0u);
    EXPECT_NE(r & feature_glossy, 0u);
    EXPECT_NE(r & feature_area_lights, 0u);
    EXPECT_EQ(r & feature_reflection, 0u);
    EXPECT_NE(feature_names(r).find("refraction"), std::string::npos);
    EXPECT_EQ(feature_names(0), "none");
}

}  // namespace
}  // namespace raylane
