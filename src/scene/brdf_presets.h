// scene: the fitted BRDF parameters of Ngan, Durand and Matusik 2005 ("Experimental Analysis of
// BRDF Models", EGSR) for the report's three materials (brdf-reference.md section 3.1).
// Scalar and packet paths share these (data, not algorithms).
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace raylane {

/// One row of brdf-reference.md table 3.1: f = rho_d / pi + rho_s S(wi, wo). Linear RGB,
/// uniform 1/1500 MERL scale (the MERL reader's per-channel factors are not applied).
struct BrdfFit {
    std::string_view material;  ///< MERL name: "nickel", "green-acrylic", "delrin"
    SpecularModel model = SpecularModel::ward;
    vec3 rho_d{0.0f};
    vec3 rho_s{0.0f};
    float lobe = 0.0f;  ///< alpha (Ward, Ward-Duer) or exponent n (Blinn-Phong)
};

/// The nine fits (three materials x Ward, Ward-Duer, Blinn-Phong), digit for digit.
std::span<const BrdfFit> brdf_fits();

/// Sets m to the fit of material `name` for the model already in m.model: c_d = rho_d, k_d = 1,
/// k_a = 0, c_s = rho_s, k_s = 1, and alpha (Ward, Ward-Duer) or exponent (Blinn-Phong).
/// Names: "nickel", "acrylic-green" (also "green-acrylic", MERL's name), "delrin" (also
/// "derlin", the report's spelling). With merl_colour, the green and blue channels of rho_d and
/// rho_s are multiplied by 1.15 and 1.66 (the MERL reader's channel scales, section 2.5).
/// Returns false, leaving m unchanged, for an unknown name or a model without fits (phong,
/// glossy_phong).
bool apply_brdf_preset(std::string_view name, Material& m, bool merl_colour = false);

/// The canonical preset names accepted by apply_brdf_preset, in table order.
std::vector<std::string> brdf_preset_names();

/// The MERL reader's green and blue channel scales relative to red (1.15 / 1500, 1.66 / 1500).
inline constexpr float merl_green_scale = 1.15f;
inline constexpr float merl_blue_scale = 1.66f;

}  // namespace raylane
