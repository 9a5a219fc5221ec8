// Test support: the scenes of the report's tests (tests/report/report_*_test.cpp).
#pragma once

#include "io/load_scene.h"
#include "scene/scene.h"

namespace raylane::test {

/// scenes/builtin.json at 32x24 pixels.
inline SceneData tiny_builtin() {
    SceneData scene = load_scene(RAYLANE_SOURCE_DIR "/scenes/builtin.json");
    scene.camera.width = 32;
    scene.camera.height = 24;
    return scene;
}

}  // namespace raylane::test
