// render: the scalar reference renderer: per pixel, per sample, one ray traced and shaded.
// Mirrored by render_packet.h.
#pragma once

#include "accel/bvh.h"
#include "render/render_params.h"
#include "scene/scene.h"

namespace raylane {

/// Renders the scene's camera at its resolution with params.spp samples per pixel.
RenderResult render_scalar(const SceneData& scene, const Accel& accel, const RenderParams& params);

}  // namespace raylane
