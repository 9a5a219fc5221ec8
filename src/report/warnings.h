// report: what a user should hear about a scene or a render that will not show what they meant
// (the render still runs): one line each, without a trailing newline.
#pragma once

#include <string>
#include <vector>

#include "accel/bvh.h"
#include "image/film.h"
#include "render/render_params.h"
#include "scene/scene.h"

namespace raylane {

/// Before a render: a scene without lights; a camera whose rays (a 32x18 grid over the frame,
/// through the pixel centres' lens centre) hit no object.
std::vector<std::string> scene_warnings(const SceneData& scene, const Accel& accel);

/// After a render: every pixel black; every sample NaN. `samples` is pixels times spp.
std::vector<std::string> render_warnings(const Film& film, const RenderStats& stats,
                                         uint64_t samples);

}  // namespace raylane
