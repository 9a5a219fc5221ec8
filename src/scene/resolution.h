// scene: a camera's image size from the width and height a user asks for.
#pragma once

#include "scene/scene.h"

namespace raylane {

/// Sets the camera's image to width x height; one of them alone (the other 0) keeps the
/// camera's aspect ratio, neither keeps its size. Throws InputError when the image would be
/// larger than max_film_side a side or max_film_pixels in all.
void apply_resolution(Camera& camera, int width, int height);

}  // namespace raylane
