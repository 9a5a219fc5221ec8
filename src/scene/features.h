// scene: what a scene uses, known after loading. The packet renderer dispatches once per frame
// to kernels compiled with only these features (shade/shade_packet.h); `raylane info` lists them.
#pragma once

#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace raylane {

/// Feature bits. The first group selects code in the packet kernels; the rest is information.
enum Feature : uint32_t {
    feature_textures = 1u << 0,     ///< image or checker textures, normal maps
    feature_area_lights = 1u << 1,  ///< rectangle, disc and box lights (random light samples)
    feature_reflection = 1u << 2,   ///< mirror materials
    feature_refraction = 1u << 3,   ///< glass
    feature_glossy = 1u << 4,       ///< glossy Phong rays
    feature_environment = 1u << 5,  ///< environment maps (scene or per object)
    feature_lens = 1u << 6,         ///< depth of field
    // information only
    feature_point_lights = 1u << 8,
    feature_directional_lights = 1u << 9,
    feature_shadows = 1u << 10,
    feature_normal_maps = 1u << 11,
    feature_analytic_shapes = 1u << 12,
    feature_meshes = 1u << 13,
    feature_fitted_brdfs = 1u << 14,
};

/// Every kernel feature (the generic kernel).
inline constexpr uint32_t kernel_features_all = (1u << 7) - 1u;

/// The features `scene` uses.
uint32_t scene_features(const SceneData& scene);

/// Space-separated names of the features in `features` ("textures area-lights ...").
std::string feature_names(uint32_t features);

}  // namespace raylane
