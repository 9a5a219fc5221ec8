// scene: detecting the features a scene uses (features.h).
#include "scene/features.h"

namespace raylane {

uint32_t scene_features(const SceneData& scene) {
    uint32_t f = 0;
    for (const Material& m : scene.materials) {
        if (m.texture >= 0 || m.normal_map >= 0) f |= feature_textures;
        if (m.normal_map >= 0) f |= feature_normal_maps;
        if (m.reflection > 0.0f) f |= feature_reflection;
        if (m.refractive) f |= feature_refraction;
        if (m.model == SpecularModel::glossy_phong) f |= feature_glossy;
        if (m.env_map >= 0) f |= feature_environment;
        if (m.model == SpecularModel::ward || m.model == SpecularModel::ward_duer ||
            m.model == SpecularModel::blinn_phong)
            f |= feature_fitted_brdfs;
    }
    for (const Light& l : scene.lights) {
        if (l.is_area()) f |= feature_area_lights;
        if (l.kind == LightKind::point) f |= feature_point_lights;
        if (l.kind == LightKind::directional) f |= feature_directional_lights;
        if (l.shadows) f |= feature_shadows;
    }
    if (scene.environment >= 0) f |= feature_environment;
    if (scene.camera.lens_radius > 0.0f) f |= feature_lens;
    for (const Object& o : scene.objects) {
        f |= o.kind == ShapeKind::mesh ? feature_meshes : feature_analytic_shapes;
    }
    return f;
}

std::string feature_names(uint32_t features) {
    static const char* const names[] = {
        "textures",    "area-lights",    "reflection",      "refraction",   "glossy",
        "environment", "depth-of-field", nullptr,           "point-lights", "directional-lights",
        "shadows",     "normal-maps",    "analytic-shapes", "meshes",       "fitted-brdfs"};
    std::string out;
    for (uint32_t bit = 0; bit < sizeof names / sizeof names[0]; ++bit) {
        if (names[bit] == nullptr || (features & (1u << bit)) == 0) continue;
        if (!out.empty()) out += ' ';
        out += names[bit];
    }
    return out.empty() ? "none" : out;
}

}  // namespace raylane
