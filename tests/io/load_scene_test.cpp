// tests for io/load_scene.cpp: good scenes give the right values, every kind of bad input gives one
// InputError line naming the file and the JSON path, and the scenes in scenes/ load.
#include "io/load_scene.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/model_path.h"
#include "scene/transform.h"
#include "support/models.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;

const char* const camera_json =
    R"("camera": {"position": [0, 1, -5], "look_at": [0, 1, 0], "fov_deg": 60})";

/// A scene with the minimal camera and the given extra top-level members.
std::string scene_with(const std::string& members) {
    return std::string("{") + camera_json + (members.empty() ? "" : ", " + members) + "}";
}

/// The message of the InputError that loading `json` throws ("" and a test failure if none).
std::string scene_error(const std::string& json, const std::string& path = "scenes/bad.json") {
    try {
        load_scene_from_string(json, path);
    } catch (const InputError& e) {
        std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        return message;
    }
    ADD_FAILURE() << "no InputError for: " << json;
    return "";
}

/// True when find_model locates `name` from `dir` (the shared models may be absent).
bool model_available(const std::string& name, const std::string& dir) {
    try {
        find_model(name, dir);
        return true;
    } catch (const InputError&) {
        return false;
    }
}

void expect_vec3_near(vec3 a, vec3 b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

vec3 apply(const mat4& m, vec3 p) { return vec3(m * glm::vec4(p, 1.0f)); }

// ---------------------------------------------------------------------------------------------
// Good scenes

TEST(LoadScene, ReadsEveryShapeKind) {
    SceneData s = load_scene_from_string(scene_with(R"(
        "materials": {"m": {}},
        "objects": [
          {"shape": "sphere", "center": [1, 2, 3], "radius": 0.5, "material": "m"},
          {"shape": "box", "min": [-1, -2, -3], "max": [1, 2, 3], "material": "m"},
          {"shape": "cylinder", "radius": 0.25, "height": 3, "material": "m"},
          {"shape": "plane", "point": [0, -1.5, 0], "normal": [0, 2, 0], "material": "m"},
          {"shape": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0.5]], "material": "m"}
        ])"),
                                         "scenes/good.json");
    ASSERT_EQ(s.objects.size(), 5u);
    const ShapeKind kinds[] = {ShapeKind::sphere, ShapeKind::box, ShapeKind::cylinder,
                               ShapeKind::plane, ShapeKind::triangle};
    for (size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(s.objects[i].kind, kinds[i]);
        EXPECT_EQ(s.objects[i].shape, 0u);
        EXPECT_EQ(s.objects[i].material, 0u);
        EXPECT_FALSE(s.objects[i].has_transform);
    }
    ASSERT_EQ(s.spheres.size(), 1u);
    EXPECT_EQ(s.spheres[0].center, vec3(1, 2, 3));
    EXPECT_EQ(s.spheres[0].radius, 0.5f);
    ASSERT_EQ(s.boxes.size(), 1u);
    EXPECT_EQ(s.boxes[0].lo, vec3(-1, -2, -3));
    EXPECT_EQ(s.boxes[0].hi, vec3(1, 2, 3));
    ASSERT_EQ(s.cylinders.size(), 1u);
    EXPECT_EQ(s.cylinders[0].radius, 0.25f);
    EXPECT_EQ(s.cylinders[0].height, 3.0f);
    ASSERT_EQ(s.planes.size(), 1u);
    EXPECT_EQ(s.planes[0].point, vec3(0, -1.5f, 0));
    EXPECT_EQ(s.planes[0].normal, vec3(0, 1, 0));  // normalised
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_EQ(s.triangles[0].p2, vec3(0, 1, 0.5f));
    EXPECT_EQ(count_triangles(s), 1u);
    EXPECT_EQ(s.source, "scenes/good.json");
}

TEST(LoadScene, AppliesTheDefaultsOfSceneH) {
    SceneData s = load_scene_from_string(scene_with(R"(
        "materials": {"plain": {}},
        "objects": [{"shape": "sphere", "radius": 1}],
        "lights": [{"type": "point", "position": [1, 2, 3]}])"),
                                         "x.json");
    const Camera camera_defaults;
    EXPECT_EQ(s.camera.up, camera_defaults.up);
    EXPECT_EQ(s.camera.fov_axis, FovAxis::vertical);
    EXPECT_EQ(s.camera.width, camera_defaults.width);
    EXPECT_EQ(s.camera.height, camera_defaults.height);
    EXPECT_EQ(s.camera.spp, camera_defaults.spp);
    EXPECT_EQ(s.background, vec3(0.0f));

    const Material m;
    ASSERT_EQ(s.materials.size(), 2u);  // "plain", then "default" for the object without one
    EXPECT_EQ(s.materials[0].name, "plain");
    EXPECT_EQ(s.materials[1].name, "default");
    for (const Material& got : s.materials) {
        EXPECT_EQ(got.c_d, m.c_d);
        EXPECT_EQ(got.k_d, m.k_d);
        EXPECT_EQ(got.k_a, m.k_a);
        EXPECT_EQ(got.c_s, m.c_s);
        EXPECT_EQ(got.k_s, m.k_s);
        EXPECT_EQ(got.exponent, m.exponent);
    }
    EXPECT_EQ(s.objects[0].material, 1u);
    EXPECT_EQ(s.spheres[0].center, vec3(0.0f));

    const Light l;
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].kind, LightKind::point);
    EXPECT_EQ(s.lights[0].position, vec3(1, 2, 3));
    EXPECT_EQ(s.lights[0].color, l.color);
    EXPECT_EQ(s.lights[0].intensity, l.intensity);
    EXPECT_EQ(s.lights[0].shadows, l.shadows);
}

TEST(LoadScene, ReadsTheWholeCameraWithEitherFovAxis) {
    for (const char* axis : {"vertical", "horizontal"}) {
        SceneData s = load_scene_from_string(
            std::string(R"({"version": 1, "description": "camera test", "camera": {
                "position": [1, 2, 3], "look_at": [1, 2, 10], "up": [0, 2, 0], "fov_deg": 90,
                "fov_axis": ")") +
                axis +
                R"(", "resolution": [1920, 1080], "spp": 16}, "background": [0.1, 0.2, 0.3]})",
            "cam.json");
        EXPECT_EQ(s.camera.position, vec3(1, 2, 3));
        EXPECT_EQ(s.camera.look_at, vec3(1, 2, 10));
        EXPECT_EQ(s.camera.up, vec3(0, 1, 0));  // normalised
        EXPECT_EQ(s.camera.fov_deg, 90.0f);
        EXPECT_EQ(s.camera.fov_axis,
                  std::string(axis) == "vertical" ? FovAxis::vertical : FovAxis::horizontal);
        EXPECT_EQ(s.camera.width, 1920);
        EXPECT_EQ(s.camera.height, 1080);
        EXPECT_EQ(s.camera.spp, 16);
        EXPECT_EQ(s.background, vec3(0.1f, 0.2f, 0.3f));
        EXPECT_TRUE(s.objects.empty());
    }
}

TEST(LoadScene, KeepsMaterialsInFileOrder) {
    SceneData s = load_scene_from_string(scene_with(R"(
        "materials": {
          "zinc": {"c_d": [0.1, 0.2, 0.3], "k_d": 0.45, "k_a": 0.1, "c_s": [0.4, 0.5, 0.6],
                   "k_s": 0.45, "exponent": 50},
          "apple": {"k_d": 0.2}},
        "objects": [{"shape": "sphere", "radius": 1, "material": "apple"},
                    {"shape": "sphere", "radius": 1, "material": "zinc"}])"),
                                         "m.json");
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.materials[0].name, "zinc");
    EXPECT_EQ(s.materials[0].c_d, vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(s.materials[0].k_d, 0.45f);
    EXPECT_EQ(s.materials[0].k_a, 0.1f);
    EXPECT_EQ(s.materials[0].c_s, vec3(0.4f, 0.5f, 0.6f));
    EXPECT_EQ(s.materials[0].k_s, 0.45f);
    EXPECT_EQ(s.materials[0].exponent, 50.0f);
    EXPECT_EQ(s.materials[1].name, "apple");
    EXPECT_EQ(s.materials[1].k_d, 0.2f);
    EXPECT_EQ(s.objects[0].material, 1u);
    EXPECT_EQ(s.objects[1].material, 0u);
}

TEST(LoadScene, ReadsLightsAndNormalisesDirections) {
    SceneData s = load_scene_from_string(scene_with(R"("lights": [
        {"type": "directional", "direction": [1, 1, -1], "color": [1, 0, 0], "intensity": 0.5,
         "shadows": false},
        {"type": "point", "position": [0, 5, 2], "color": [0.5, 0.6, 0.7], "intensity": 30}])"),
                                         "l.json");
    ASSERT_EQ(s.lights.size(), 2u);
    const Light& d = s.lights[0];
    EXPECT_EQ(d.kind, LightKind::directional);
    float c = float(1.0 / std::sqrt(3.0));
    expect_vec3_near(d.direction, vec3(c, c, -c), 1e-7f);
    EXPECT_NEAR(glm::length(d.direction), 1.0f, 1e-6f);
    EXPECT_EQ(d.color, vec3(1, 0, 0));
    EXPECT_EQ(d.intensity, 0.5f);
    EXPECT_FALSE(d.shadows);
    const Light& p = s.lights[1];
    EXPECT_EQ(p.kind, LightKind::point);
    EXPECT_EQ(p.position, vec3(0, 5, 2));
    EXPECT_EQ(p.color, vec3(0.5f, 0.6f, 0.7f));
    EXPECT_EQ(p.intensity, 30.0f);
    EXPECT_TRUE(p.shadows);
}

TEST(LoadScene, AppliesScaleThenRotationThenTranslation) {
    SceneData s = load_scene_from_string(scene_with(R"("objects": [
        {"shape": "sphere", "radius": 1, "transform": {"translate": [10, 20, 30],
         "rotate": [{"axis": "z", "deg": 90}], "scale": [2, 3, 4]}},
        {"shape": "sphere", "radius": 1, "transform": {"scale": 2}}])"),
                                         "t.json");
    const Object& o = s.objects[0];
    EXPECT_TRUE(o.has_transform);
    // (1, 2, 3) -> scale (2, 6, 12) -> Rz(90): (x, y, z) -> (-y, x, z) = (-6, 2, 12) -> + t.
    expect_vec3_near(apply(o.world_from_object, vec3(1, 2, 3)), vec3(4, 22, 42), 1e-5f);
    expect_vec3_near(apply(o.object_from_world, vec3(4, 22, 42)), vec3(1, 2, 3), 1e-5f);
    expect_vec3_near(apply(s.objects[1].world_from_object, vec3(1, 2, 3)), vec3(2, 4, 6), 0.0f);
}

TEST(LoadScene, ReadsTheRotateListAsAProductLastAppliedFirst) {
    SceneData s = load_scene_from_string(scene_with(R"("objects": [
        {"shape": "sphere", "radius": 1, "transform": {"rotate": [
           {"axis": "z", "deg": 90}, {"axis": "y", "deg": -75}]}}])"),
                                         "r.json");
    // Ry(-75) maps +x to (cos 75, 0, sin 75); then Rz(90) maps (x, y, z) to (-y, x, z).
    double c = std::cos(75.0 * M_PI / 180.0), sn = std::sin(75.0 * M_PI / 180.0);
    expect_vec3_near(apply(s.objects[0].world_from_object, vec3(1, 0, 0)),
                     vec3(0.0f, float(c), float(sn)), 1e-6f);
}

TEST(LoadScene, ReadsRotateDegAsXThenYThenZ) {
    SceneData s = load_scene_from_string(scene_with(R"("objects": [
        {"shape": "sphere", "radius": 1, "transform": {"rotate_deg": [90, 90, 0]}}])"),
                                         "r.json");
    // Rx(90) maps +y to +z, then Ry(90) maps +z to +x. (The other order would give +z.)
    expect_vec3_near(apply(s.objects[0].world_from_object, vec3(0, 1, 0)), vec3(1, 0, 0), 1e-6f);
}

TEST(LoadScene, ReportsAnExplicitIdentityTransformAsNone) {
    SceneData s = load_scene_from_string(scene_with(R"("objects": [
        {"shape": "box", "min": [0, 0, 0], "max": [1, 1, 1], "transform": {"scale": 1,
         "translate": [0, 0, 0], "rotate": []}}])"),
                                         "i.json");
    EXPECT_FALSE(s.objects[0].has_transform);
}

// ---------------------------------------------------------------------------------------------
// Bad scenes: one line, "file: $.path: reason"

struct BadCase {
    const char* members;  ///< top-level members after the camera
    const char* path;     ///< expected JSON path
    const char* reason;   ///< expected start of the reason
};

TEST(LoadScene, NamesTheFileAndTheJsonPathOfEveryBadValue) {
    const BadCase cases[] = {
        {R"("lights_": [])", "$.lights_", "unknown key"},
        {R"("materials": {"gold": {"kd": 1}})", "$.materials.gold.kd", "unknown key"},
        {R"("materials": {"my gold": {"kd": 1}})", R"($.materials["my gold"].kd)", "unknown key"},
        {R"("objects": [{"shape": "sphere", "radius": 1, "radiu": 1}])", "$.objects[0].radiu",
         "unknown key"},
        {R"("objects": [{"shape": "sphere", "radius": 1, "transform": {"move": [1, 2, 3]}}])",
         "$.objects[0].transform.move", "unknown key"},
        {R"("lights": [{"type": "point", "position": [0, 0, 0], "power": 1}])", "$.lights[0].power",
         "unknown key"},
        {R"("objects": [{"shape": "sphere", "radius": "1"}])", "$.objects[0].radius",
         "must be a number, got a string"},
        {R"("objects": [{"shape": "sphere", "center": [1, 2], "radius": 1}])",
         "$.objects[0].center", "must be an array of 3 numbers"},
        {R"("objects": [{"shape": "sphere", "center": [1, null, 3], "radius": 1}])",
         "$.objects[0].center[1]", "must be a number, got null"},
        {R"("objects": {})", "$.objects", "must be an array, got an object"},
        {R"("objects": [3])", "$.objects[0]", "must be an object, got a number"},
        {R"("objects": [{"shape": "sphere"}])", "$.objects[0].radius", "missing (required)"},
        {R"("objects": [{"radius": 1}])", "$.objects[0].shape", "missing (required)"},
        {R"("objects": [{"shape": "box", "min": [0, 0, 0]}])", "$.objects[0].max",
         "missing (required)"},
        {R"("objects": [{"shape": "torus"}])", "$.objects[0].shape", "must be one of"},
        {R"("objects": [{"shape": "sphere", "radius": -1}])", "$.objects[0].radius",
         "must be > 0, got -1"},
        {R"("objects": [{"shape": "cylinder", "radius": 1, "height": 0}])", "$.objects[0].height",
         "must be > 0, got 0"},
        {R"("objects": [{"shape": "sphere", "radius": 1e39}])", "$.objects[0].radius",
         "1e+39 is outside the float range"},
        {R"("objects": [{"shape": "box", "min": [0, 0, 0], "max": [1, -1, 1]}])",
         "$.objects[0].max", "must be >= min"},
        {R"("objects": [{"shape": "plane", "normal": [0, 0, 0]}])", "$.objects[0].normal",
         "must not be the zero vector"},
        {R"("objects": [{"shape": "triangle", "vertices": [[0, 0, 0], [1, 1, 1], [2, 2, 2]]}])",
         "$.objects[0].vertices", "the triangle has zero area"},
        {R"("objects": [{"shape": "triangle", "vertices": [[0, 0, 0], [1, 1, 1]]}])",
         "$.objects[0].vertices", "must be an array of 3 points"},
        {R"("materials": {"floor": {}, "dragon": {}},
            "objects": [{"shape": "sphere", "radius": 1, "material": "floor"},
                        {"shape": "sphere", "radius": 1, "material": "gold"}])",
         "$.objects[1].material", R"(no material named "gold" (known: floor, dragon))"},
        {R"("objects": [{"shape": "sphere", "radius": 1, "material": "x"}])",
         "$.objects[0].material", R"(no material named "x" (known: none))"},
        {R"("objects": [{"shape": "sphere", "radius": 1, "transform": {"scale": [1, 0, 1]}}])",
         "$.objects[0].transform.scale", "must not be zero"},
        {R"("objects": [{"shape": "sphere", "radius": 1, "transform": {
            "rotate": [], "rotate_deg": [0, 0, 0]}}])",
         "$.objects[0].transform.rotate_deg", "give either rotate or rotate_deg"},
        {R"("objects": [{"shape": "sphere", "radius": 1, "transform": {
            "rotate": [{"axis": "w", "deg": 3}]}}])",
         "$.objects[0].transform.rotate[0].axis", "must be one of \"x\", \"y\", \"z\""},
        {R"("objects": [{"shape": "sphere", "radius": 1, "transform": {
            "rotate": [{"axis": "x"}]}}])",
         "$.objects[0].transform.rotate[0].deg", "missing (required)"},
        {R"("lights": [{"type": "directional", "direction": [0, 0, 0]}])", "$.lights[0].direction",
         "must not be the zero vector"},
        {R"("lights": [{"type": "spot", "position": [0, 0, 0]}])", "$.lights[0].type",
         "must be one of \"point\", \"directional\""},
        {R"("lights": [{"type": "directional", "direction": [0, 1, 0], "color": [2, 2, 2],
            "intensity": 3e38}])",
         "$.lights[0]", "the light's color times its intensity overflows the float range"},
        {R"("lights": [{"type": "point", "position": [0, 0, 0], "intensity": -2}])",
         "$.lights[0].intensity", "must be >= 0, got -2"},
        {R"("lights": [{"type": "point", "position": [0, 0, 0], "color": [1, -0.5, 1]}])",
         "$.lights[0].color[1]", "must be >= 0, got -0.5"},
        {R"("lights": [{"type": "point", "position": [0, 0, 0], "shadows": 1}])",
         "$.lights[0].shadows", "must be true or false"},
        {R"("background": [0, 0, -1])", "$.background[2]", "must be >= 0"},
        {R"("version": 2)", "$.version", "unsupported version 2"},
        {R"("materials": {"m": {"exponent": -1}})", "$.materials.m.exponent", "must be >= 0"},
        {R"("objects": [{"shape": "mesh"}])", "$.objects[0].file", "missing (required)"},
        {R"("objects": [{"shape": "mesh", "file": "m.obj", "radius": 1}])", "$.objects[0].radius",
         "unknown key"},
    };
    for (const BadCase& c : cases) {
        std::string expected = std::string("scenes/bad.json: ") + c.path + ": " + c.reason;
        std::string got = scene_error(scene_with(c.members));
        EXPECT_EQ(got.substr(0, expected.size()), expected) << "for " << c.members;
    }
}

TEST(LoadScene, NamesTheJsonPathOfBadCameraValues) {
    struct CameraCase {
        const char* camera;
        const char* path;
        const char* reason;
    };
    const CameraCase cases[] = {
        {R"({"look_at": [0, 0, 1], "fov_deg": 60})", "$.camera.position", "missing (required)"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60, "fov": 1})",
         "$.camera.fov", "unknown key"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 180})", "$.camera.fov_deg",
         "must be between 0 and 180"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60, "fov_axis": "diag"})",
         "$.camera.fov_axis", "must be one of"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60, "resolution": [0, 5]})",
         "$.camera.resolution[0]", "must be an integer from 1 to 32768, got 0"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60,
            "resolution": [640, 32769]})",
         "$.camera.resolution[1]", "must be an integer from 1 to 32768, got 32769"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60,
            "resolution": [640.5, 480]})",
         "$.camera.resolution[0]", "must be an integer, got a number"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60,
            "resolution": [-640, 480]})",
         "$.camera.resolution[0]", "must be an integer from 1 to 32768, got -640"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60,
            "resolution": [32768, 8193]})",
         "$.camera.resolution", "more than 2^28 pixels (32768x8193)"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60, "resolution": [640]})",
         "$.camera.resolution", "must be an array [width, height]"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60, "spp": 0})",
         "$.camera.spp", "must be an integer from 1 to"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60,
            "spp": 99999999999999999999})",
         "$.camera.spp", "must be an integer, got a number"},
        {R"({"position": [0, 0, 1], "look_at": [0, 0, 1], "fov_deg": 60})", "$.camera.look_at",
         "must differ from the camera position"},
        {R"({"position": [0, 0, 0], "look_at": [0, 5, 0], "fov_deg": 60})", "$.camera.look_at",
         "the view direction is parallel to up"},
        {R"({"position": [0, 0, 0], "look_at": [0, 0, 1], "up": [0, 0, -2], "fov_deg": 60})",
         "$.camera.up", "the view direction is parallel to up"},
    };
    for (const CameraCase& c : cases) {
        std::string expected = std::string("scenes/bad.json: ") + c.path + ": " + c.reason;
        std::string got = scene_error(std::string(R"({"camera": )") + c.camera + "}");
        EXPECT_EQ(got.substr(0, expected.size()), expected) << "for " << c.camera;
    }
    EXPECT_EQ(scene_error("{}"), "scenes/bad.json: $.camera: missing (required)");
    EXPECT_EQ(scene_error("[]"), "scenes/bad.json: $: must be an object, got an empty array");
}

TEST(LoadScene, MessagesSayHowLongAnArrayIsAndCutLongKeysAndSyntax) {
    EXPECT_EQ(scene_error(scene_with(R"("objects": [{"shape": "sphere", "center": [1, 2]}])")),
              "scenes/bad.json: $.objects[0].center: must be an array of 3 numbers, got an "
              "array of 2");
    // a key of a million characters is named by its first 60
    const std::string key(1000000, 'k');
    EXPECT_EQ(scene_error(scene_with("\"" + key + "\": 1")),
              "scenes/bad.json: $[\"" + key.substr(0, 60) +
                  "...\"]: unknown key (expected: version, description, camera, background, "
                  "environment, shading, tonemap, materials, objects, lights)");
    // errors in a megabyte-long token quote 200 characters of it at most
    for (const std::string& json : {"{\"camera\": \"" + std::string(1000000, 'a'),
                                    "{\"camera\": " + std::string(1000000, '9')}) {
        const std::string message = scene_error(json);
        EXPECT_LT(message.size(), 300u) << message.substr(0, 300);
        EXPECT_EQ(message.substr(message.size() - 3), "...") << message.substr(0, 300);
    }
}

TEST(LoadScene, RejectsDuplicateKeysWithTheirPath) {
    EXPECT_EQ(scene_error(R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1],
                                      "fov_deg": 60, "fov_deg": 70}})"),
              "scenes/bad.json: $.camera.fov_deg: duplicate key");
    EXPECT_EQ(scene_error(scene_with(R"("objects": [{"shape": "box"}, {"shape": "sphere",
                                      "radius": 1, "radius": 2}])")),
              "scenes/bad.json: $.objects[1].radius: duplicate key");
}

TEST(LoadScene, GivesLineAndColumnForMalformedJson) {
    std::string got = scene_error("{\n  \"camera\": tru\n}");
    EXPECT_EQ(got.rfind("scenes/bad.json:2:", 0), 0u) << got;
    EXPECT_NE(got.find("syntax error"), std::string::npos) << got;

    got = scene_error("{\"camera\": {\"fov_deg\": NaN}}");
    EXPECT_EQ(got.rfind("scenes/bad.json:1:", 0), 0u) << got;

    got = scene_error(scene_with(R"("background": [1e400, 0, 0])"));
    EXPECT_EQ(got.rfind("scenes/bad.json:1:", 0), 0u) << got;
    EXPECT_NE(got.find("number overflow"), std::string::npos) << got;

    got = scene_error("");
    EXPECT_EQ(got.rfind("scenes/bad.json:1:1: ", 0), 0u) << got;

    got = scene_error(scene_with("") + " trailing");
    EXPECT_EQ(got.rfind("scenes/bad.json:1:", 0), 0u) << got;

    got = scene_error("{\"camera\": \"\xff\xfe\"}");  // invalid UTF-8: still one printable line
    for (char c : got) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << got;
}

TEST(LoadScene, KeepsKeysWithControlCharactersOnOneLine) {
    std::string got = scene_error(scene_with(R"("bad\nkey": 1)"));
    EXPECT_EQ(
        got,
        R"(scenes/bad.json: $["bad\u000akey"]: unknown key (expected: version, )"
        R"(description, camera, background, environment, shading, tonemap, materials, objects, )"
        R"(lights))");
}

TEST(LoadScene, RejectsDeepNestingQuicklyWithoutCrashing) {
    for (const std::string& open : {std::string("["), std::string("{\"a\":")}) {
        std::string text;
        for (int i = 0; i < 100000; ++i) text += open;
        auto start = std::chrono::steady_clock::now();
        std::string got = scene_error(text);
        double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        size_t column = open.size() * size_t(max_scene_json_depth) + 1;
        EXPECT_EQ(got, "scenes/bad.json:1:" + std::to_string(column) +
                           ": JSON nested deeper than 64 levels");
        EXPECT_LT(seconds, 1.0);
    }
}

TEST(LoadScene, AcceptsNestingUpToTheLimit) {
    // The root object is level 1, so "objects": followed by n brackets reaches level 1 + n.
    auto nested = [](int n) { return std::string(size_t(n), '[') + std::string(size_t(n), ']'); };
    for (int n : {max_scene_json_depth - 2, max_scene_json_depth - 1}) {
        EXPECT_EQ(scene_error(scene_with("\"objects\": " + nested(n))),
                  "scenes/bad.json: $.objects[0]: must be an object, got an array of 1");
    }
    std::string too_deep = scene_error(scene_with("\"objects\": " + nested(max_scene_json_depth)));
    EXPECT_NE(too_deep.find("JSON nested deeper than 64 levels"), std::string::npos) << too_deep;
}

TEST(LoadScene, ReportsUnreadableFiles) {
    test::TempDir dir("raylane_load_scene_");
    std::string missing = (dir.path / "missing.json").string();
    try {
        load_scene(missing);
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(missing + ": cannot read", 0), 0u) << e.what();
    }
    try {
        load_scene(dir.path.string());
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(dir.path.string() + ": cannot read", 0), 0u)
            << e.what();
    }
    test::write_file(dir.path / "bad.json", "{\"camera\": 1}");
    std::string bad = (dir.path / "bad.json").string();
    try {
        load_scene(bad);
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), bad + ": $.camera: must be an object, got a number");
    }
}

// ---------------------------------------------------------------------------------------------
// Meshes

const char* const quad_obj =
    "v 0 0 0\nv 4 0 0\nv 4 2 0\nv 0 2 -2\n"
    "vn 0 0 1\n"
    "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";

TEST(LoadScene, FitsThenTransformsAndBakesMeshes) {
    test::TempDir dir("raylane_load_scene_");
    test::write_file(dir.path / "quad.obj", quad_obj);
    test::write_file(dir.path / "s.json", scene_with(R"("objects": [
        {"shape": "mesh", "file": "quad.obj",
         "fit": {"size": 1, "axis": "x", "offset": [0, 0.5, 0]},
         "transform": {"translate": [10, 0, 0]}},
        {"shape": "mesh", "file": "quad.obj", "fit": {"scale": 2}},
        {"shape": "mesh", "file": "quad.obj"}])"));
    SceneData s = load_scene((dir.path / "s.json").string());
    ASSERT_EQ(s.meshes.size(), 3u);
    ASSERT_EQ(s.objects.size(), 3u);
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(s.objects[i].kind, ShapeKind::mesh);
        EXPECT_EQ(s.objects[i].shape, i);
        EXPECT_FALSE(s.objects[i].has_transform);  // meshes are in world space
        EXPECT_EQ(s.meshes[i].triangle_count(), 2u);
    }
    EXPECT_EQ(count_triangles(s), 6u);
    // Bounds x 0..4, y 0..2, z -2..0: bottom centre (2, 0, -1). MeshData 0: scale 1/4, +(0, 0.5,
    // 0), then +(10, 0, 0).
    const MeshData& a = s.meshes[0];
    ASSERT_EQ(a.positions.size(), 4u);
    expect_vec3_near(a.positions[0], vec3(9.5f, 0.5f, 0.25f), 1e-6f);
    expect_vec3_near(a.positions[2], vec3(10.5f, 1.0f, 0.25f), 1e-6f);
    expect_vec3_near(a.positions[3], vec3(9.5f, 1.0f, -0.25f), 1e-6f);
    // MeshData 1: scale 2 about the bottom centre.
    expect_vec3_near(s.meshes[1].positions[1], vec3(4, 0, 2), 1e-6f);
    // MeshData 2: unchanged.
    EXPECT_EQ(s.meshes[2].positions[3], vec3(0, 2, -2));
    // Uniform positive scale and translation leave normals as they are.
    ASSERT_FALSE(a.normals.empty());
    expect_vec3_near(a.normals[0], vec3(0, 0, 1), 1e-7f);
}

// The last object that names a file takes the loaded mesh instead of a copy (read_mesh in
// load_scene_objects.cpp), counted by the resolved path: a file named two ways is one file.
TEST(LoadScene, GivesEveryObjectOfAFileTheWholeMesh) {
    test::TempDir dir("raylane_load_scene_");
    test::write_file(dir.path / "quad.obj", quad_obj);
    test::write_file(dir.path / "s.json", scene_with(R"("objects": [
        {"shape": "mesh", "file": "quad.obj"},
        {"shape": "mesh", "file": "./quad.obj"},
        {"shape": "mesh", "file": "quad.obj", "transform": {"translate": [1, 0, 0]}},
        {"shape": "mesh", "file": "./quad.obj"}])"));
    SceneData s = load_scene((dir.path / "s.json").string());
    ASSERT_EQ(s.meshes.size(), 4u);
    for (size_t i = 0; i < 4; ++i) {
        ASSERT_EQ(s.meshes[i].positions.size(), 4u) << i;
        ASSERT_EQ(s.meshes[i].triangle_count(), 2u) << i;
        const vec3 shift(i == 2 ? 1.0f : 0.0f, 0.0f, 0.0f);
        EXPECT_EQ(s.meshes[i].positions[3], vec3(0, 2, -2) + shift) << i;
        EXPECT_EQ(s.meshes[i].positions[1], vec3(4, 0, 0) + shift) << i;
    }
}

TEST(LoadScene, NamesTheJsonPathOfBadFits) {
    test::TempDir dir("raylane_load_scene_");
    test::write_file(dir.path / "quad.obj", quad_obj);
    test::write_file(dir.path / "flat.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n");
    const BadCase cases[] = {
        {R"("objects": [{"shape": "mesh", "file": "quad.obj", "fit": {"size": 1, "scale": 2}}])",
         "$.objects[0].fit.scale", "give either size or scale"},
        {R"("objects": [{"shape": "mesh", "file": "quad.obj", "fit": {"offset": [0, 0, 0]}}])",
         "$.objects[0].fit", "needs \"size\" or \"scale\""},
        {R"("objects": [{"shape": "mesh", "file": "quad.obj", "fit": {"scale": 2, "axis": "x"}}])",
         "$.objects[0].fit.axis", "only goes with \"size\""},
        {R"("objects": [{"shape": "mesh", "file": "quad.obj", "fit": {"size": -1}}])",
         "$.objects[0].fit.size", "must be > 0"},
        {R"("objects": [{"shape": "mesh", "file": "flat.obj", "fit": {"size": 1, "axis": "y"}}])",
         "$.objects[0].fit", "the mesh has no extent along y"},
        {R"("objects": [{"shape": "mesh", "file": "quad.obj", "fit": {"size": 1, "axis": "w"}}])",
         "$.objects[0].fit.axis", "must be one of"},
    };
    std::string scene_path = (dir.path / "bad.json").string();
    for (const BadCase& c : cases) {
        std::string expected = scene_path + ": " + c.path + ": " + c.reason;
        std::string got = scene_error(scene_with(c.members), scene_path);
        EXPECT_EQ(got.substr(0, expected.size()), expected) << "for " << c.members;
    }
}

TEST(LoadScene, GivesTheModelSearchMessageWhenAMeshIsMissing) {
    test::TempDir dir("raylane_load_scene_");
    std::string scene_path = (dir.path / "s.json").string();
    std::string got = scene_error(scene_with(R"("objects": [
        {"shape": "sphere", "radius": 1},
        {"shape": "mesh", "file": "no_such_model_4711.ply"}])"),
                                  scene_path);
    std::string prefix = scene_path + ": $.objects[1].file: ";
    EXPECT_EQ(got.rfind(prefix, 0), 0u) << got;
    EXPECT_NE(got.find("no_such_model_4711.ply"), std::string::npos) << got;
    EXPECT_NE(got.find(dir.path.string()), std::string::npos) << "lists the scene folder: " << got;
}

TEST(LoadScene, PassesABrokenMeshFilesErrorThrough) {
    test::TempDir dir("raylane_load_scene_");
    test::write_file(dir.path / "broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
    std::string scene_path = (dir.path / "s.json").string();
    std::string got = scene_error(
        scene_with(R"("objects": [{"shape": "mesh", "file": "broken.obj"}])"), scene_path);
    EXPECT_NE(got.find("broken.obj"), std::string::npos) << got;
    EXPECT_EQ(got.rfind(scene_path, 0), std::string::npos) << "the mesh's own message: " << got;
}

// ---------------------------------------------------------------------------------------------
// The scenes in scenes/

const std::string scenes_dir = RAYLANE_SOURCE_DIR "/scenes";

TEST(SceneFiles, BuiltinJsonLoadsWithoutAModel) {
    SceneData s = load_scene(scenes_dir + "/builtin.json");
    EXPECT_TRUE(s.meshes.empty());
    EXPECT_EQ(count_triangles(s), 1u);
    EXPECT_EQ(s.lights.size(), 2u);
}

TEST(SceneFiles, TheExampleOfTheFormatDocumentLoads) {
    std::ifstream doc(RAYLANE_SOURCE_DIR "/docs/scene-format.md");
    std::string text((std::istreambuf_iterator<char>(doc)), std::istreambuf_iterator<char>());
    size_t begin = text.find("```json\n");
    ASSERT_NE(begin, std::string::npos);
    begin += 8;
    size_t end = text.find("```", begin);
    ASSERT_NE(end, std::string::npos);
    if (!model_available("dragon.ply", scenes_dir))
        RAYLANE_MODEL_MISSING() << "dragon.ply not found";
    SceneData s = load_scene_from_string(text.substr(begin, end - begin), scenes_dir + "/doc.json");
    EXPECT_EQ(s.objects.size(), 6u);
    EXPECT_EQ(s.lights.size(), 2u);
}

/// Undoes T(translate) * Ry(deg) on a point: Ry(-deg) * (p - translate).
vec3 undo_ty(vec3 p, vec3 translate, double deg) {
    double r = -deg * M_PI / 180.0, c = std::cos(r), sn = std::sin(r);
    glm::dvec3 q = glm::dvec3(p) - glm::dvec3(translate);
    return vec3(glm::dvec3(c * q.x + sn * q.z, q.y, -sn * q.x + c * q.z));
}

TEST(SceneFiles, DragonIsNormalisedAsInTheReport) {
    if (!model_available("dragon.ply", scenes_dir))
        RAYLANE_MODEL_MISSING() << "dragon.ply not found";
    SceneData s = load_scene(scenes_dir + "/dragon.json");
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(count_triangles(s), 100000u);
    EXPECT_EQ(s.camera.width, 1920);
    EXPECT_EQ(s.camera.height, 1080);
    EXPECT_EQ(s.camera.spp, 1);
    int point_lights = 0;
    for (const Light& l : s.lights) point_lights += l.kind == LightKind::point && l.shadows;
    EXPECT_EQ(point_lights, 2);
    // Back in the fitted frame (before T(0, -0.2, 1) * Ry(-75)): length 1 along x, base at
    // y = 0, centred in x and z (report-scenes.md section 4).
    Aabb box;
    for (vec3 p : s.meshes[0].positions) box.grow(undo_ty(p, vec3(0, -0.2f, 1), -75.0));
    EXPECT_NEAR(box.extent().x, 1.0f, 1e-5f);
    EXPECT_NEAR(box.lo.y, 0.0f, 1e-5f);
    EXPECT_NEAR(box.center().x, 0.0f, 1e-5f);
    EXPECT_NEAR(box.center().z, 0.0f, 1e-5f);
    EXPECT_NEAR(box.extent().y / box.extent().x, 9.9399 / 14.0934, 1e-3);
}

TEST(SceneFiles, BunnySitsOnTheFloorAsInTheReport) {
    if (!model_available("bunny.ply", scenes_dir)) RAYLANE_MODEL_MISSING() << "bunny.ply not found";
    SceneData s = load_scene(scenes_dir + "/bunny.json");
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(count_triangles(s), 69451u);
    ASSERT_EQ(s.planes.size(), 1u);
    Aabb world = mesh_bounds(s.meshes[0]);
    EXPECT_NEAR(world.lo.y, s.planes[0].point.y, 1e-5f);  // lowest point on the floor
    // Scaled by 30 about the bottom centre, then moved by (-0.5, 0.1, 0) (section 4).
    Aabb box;
    for (vec3 p : s.meshes[0].positions) box.grow(undo_ty(p, vec3(0, -1.6f, 6), -175.0));
    EXPECT_NEAR(box.lo.y, 0.1f, 1e-5f);
    EXPECT_NEAR(box.extent().y, 30.0f * (0.18732f - 0.03299f), 1e-3f);
}

}  // namespace
}  // namespace raylane
