// Test support: a scene's camera narrowed to a few pixels, for renders that tests can afford.
#pragma once

#include <algorithm>

#include "scene/scene.h"

namespace raylane::test {

/// `scene` rendered `width` pixels wide, its aspect ratio kept (at least one row).
inline SceneData small_scene(SceneData scene, int width) {
    scene.camera.height = std::max(1, scene.camera.height * width / scene.camera.width);
    scene.camera.width = width;
    return scene;
}

}  // namespace raylane::test
