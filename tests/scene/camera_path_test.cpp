// Tests of camera animation (scene/camera_path.h) and of its scene format.
#include "scene/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/rng.h"
#include "io/load_scene.h"
#include "support/input_error.h"

namespace raylane {
namespace {

Camera still() {
    Camera c;
    c.position = vec3(0.0f, 1.0f, -4.0f);
    c.look_at = vec3(0.0f, 1.0f, 0.0f);
    c.fov_deg = 40.0f;
    c.focal_distance = 4.0f;
    return c;
}

TEST(CameraPath, AStillHasOneFrameAndItsOwnCamera) {
    const CameraPath none;
    EXPECT_EQ(frame_count(none), 1);
    const Camera c = camera_at_frame(still(), none, 0);
    EXPECT_EQ(c.position, still().position);
    EXPECT_EQ(c.fov_deg, still().fov_deg);
}

TEST(CameraPath, TurntableOrbitsTheLookAtPointAboutUp) {
    CameraPath path;
    path.turntable_frames = 8;
    EXPECT_EQ(frame_count(path), 8);
    const Camera c0 = camera_at_frame(still(), path, 0);
    EXPECT_NEAR(c0.position.z, -4.0f, 1e-6f);
    const Camera c2 = camera_at_frame(still(), path, 2);  // a quarter turn about +y
    EXPECT_NEAR(c2.position.x, -4.0f, 1e-5f);
    EXPECT_NEAR(c2.position.y, 1.0f, 1e-6f);
    EXPECT_NEAR(c2.position.z, 0.0f, 1e-5f);
    const Camera c4 = camera_at_frame(still(), path, 4);  // half a turn
    EXPECT_NEAR(c4.position.z, 4.0f, 1e-5f);
    EXPECT_EQ(c4.look_at, still().look_at);
}

TEST(CameraPath, KeysArePassedThroughAtTheirTimes) {
    for (Interpolation kind : {Interpolation::linear, Interpolation::catmull_rom}) {
        CameraPath path;
        path.interpolation = kind;
        path.fps = 4.0f;
        for (int i = 0; i < 4; ++i) {
            CameraKey k;
            k.time = float(i) * 0.5f;  // a key every 2 frames
            k.position = vec3(float(i * i), 1.0f, -4.0f);
            k.look_at = vec3(0.0f, 1.0f, 0.0f);
            k.fov_deg = 30.0f + 10.0f * float(i);
            path.keys.push_back(k);
        }
        EXPECT_EQ(frame_count(path), 7);  // 1.5 s at 4 frames a second, both ends
        for (int i = 0; i < 4; ++i) {
            const Camera c = camera_at_frame(still(), path, 2 * i);
            EXPECT_NEAR(c.position.x, float(i * i), 1e-5f) << i;
            EXPECT_NEAR(c.fov_deg, 30.0f + 10.0f * float(i), 1e-4f) << i;
            EXPECT_NEAR(c.focal_distance, glm::length(c.look_at - c.position), 1e-5f);
        }
        // between keys: linear halves the way; Catmull-Rom bends with the keys around it
        const float mid = camera_at_frame(still(), path, 3).position.x;  // between x = 1 and 4
        if (kind == Interpolation::linear)
            EXPECT_NEAR(mid, 2.5f, 1e-5f);
        else
            EXPECT_NEAR(mid, 2.25f, 1e-5f);  // x = i^2 is a parabola: the spline follows it
    }
}

TEST(CameraPath, FramesDrawTheirOwnNumbers) {
    EXPECT_EQ(frame_seed(7, 0), 7u);  // a still renders as it always did
    EXPECT_NE(frame_seed(7, 1), frame_seed(7, 2));
    EXPECT_NE(frame_seed(7, 1), 7u);
    EXPECT_EQ(frame_seed(7, 5), frame_seed(7, 5));
}

std::string scene_with_camera(const std::string& extra) {
    return R"({"camera": {"position": [0, 1, -4], "look_at": [0, 1, 0], "fov_deg": 40)" + extra +
           "}}";
}

TEST(CameraPath, SceneFormatReadsPathsAndTurntables) {
    const SceneData a =
        load_scene_from_string(scene_with_camera(R"(, "turntable": {"frames": 36})"), "t.json");
    EXPECT_EQ(frame_count(a.camera_path), 36);
    const SceneData b = load_scene_from_string(
        scene_with_camera(R"(, "path": {"fps": 10, "interpolation": "linear", "keys": [
            {"time": 0, "position": [0, 1, -4], "look_at": [0, 1, 0]},
            {"time": 2, "position": [4, 1, 0], "look_at": [0, 1, 0], "fov_deg": 60}]})"),
        "p.json");
    EXPECT_EQ(frame_count(b.camera_path), 21);
    EXPECT_EQ(b.camera_path.interpolation, Interpolation::linear);
    EXPECT_EQ(b.camera_path.keys[0].fov_deg, 40.0f);  // the camera's, when a key gives none
    EXPECT_EQ(b.camera_path.keys[1].fov_deg, 60.0f);
}

TEST(CameraPath, BadPathsGiveOneClearError) {
    using test::input_error_of;
    auto expect_error = [](auto load, const std::string& text) {
        const std::string e = input_error_of(load);
        EXPECT_NE(e.find(text), std::string::npos) << e;
    };
    expect_error(
        [] {
            load_scene_from_string(scene_with_camera(R"(, "turntable": {"frames": 0})"), "t.json");
        },
        "t.json: $.camera.turntable.frames");
    expect_error(
        [] {
            load_scene_from_string(scene_with_camera(R"(, "path": {"keys": [
                {"time": 1, "position": [0, 1, -4], "look_at": [0, 1, 0]},
                {"time": 1, "position": [4, 1, 0], "look_at": [0, 1, 0]}]})"),
                                   "t.json");
        },
        "t.json: $.camera.path.keys[1].time: must be later than the key before it");
    expect_error(
        [] {
            load_scene_from_string(scene_with_camera(R"(, "path": {"keys": [
                {"time": 0, "position": [0, 1, -4], "look_at": [0, 1, 0]}]})"),
                                   "t.json");
        },
        "t.json: $.camera.path.keys: must be an array of two or more keys");
    expect_error(
        [] {
            load_scene_from_string(scene_with_camera(R"(, "path": {"keys": [
                {"time": 0, "position": [0, 1, 0], "look_at": [0, 1, 0]},
                {"time": 1, "position": [4, 1, 0], "look_at": [0, 1, 0]}]})"),
                                   "t.json");
        },
        "t.json: $.camera.path.keys[0].look_at: must differ from the key's position");
    expect_error(
        [] {
            load_scene_from_string(scene_with_camera(R"(, "turntable": {"frames": 3}, "path": {})"),
                                   "t.json");
        },
        "a camera moves along a path or turns, not both");
}

}  // namespace
}  // namespace raylane
