// scene: the Ngan et al. 2005 fits of brdf-reference.md table 3.1 (transcribed by
// bsdfbenchmark/bbm fits/ngan_*.fit and AndreasVanBarel/RayTracer src/material/*.java).
#include "scene/brdf_presets.h"

#include <array>

namespace raylane {

namespace {

constexpr SpecularModel ward = SpecularModel::ward;
constexpr SpecularModel ward_duer = SpecularModel::ward_duer;
constexpr SpecularModel blinn_phong = SpecularModel::blinn_phong;

const std::array<BrdfFit, 9> fits = {{
    {"nickel", ward, {0.0221f, 0.0178f, 0.0107f}, {0.204f, 0.154f, 0.0946f}, 0.0432f},
    {"nickel", ward_duer, {0.0388f, 0.0291f, 0.0159f}, {0.107f, 0.0828f, 0.054f}, 0.0424f},
    {"nickel", blinn_phong, {0.0301f, 0.0257f, 0.0173f}, {0.0665f, 0.0486f, 0.0285f}, 1040.0f},
    {"green-acrylic", ward, {0.0164f, 0.0641f, 0.0238f}, {0.0101f, 0.00793f, 0.00495f}, 0.0141f},
    {"green-acrylic",
     ward_duer,
     {0.0165f, 0.064f, 0.0239f},
     {0.0068f, 0.00548f, 0.00335f},
     0.0137f},
    {"green-acrylic",
     blinn_phong,
     {0.0183f, 0.0657f, 0.0248f},
     {0.00161f, 0.00121f, 0.000781f},
     28400.0f},
    {"delrin", ward, {0.293f, 0.244f, 0.146f}, {0.0348f, 0.0295f, 0.0202f}, 0.162f},
    {"delrin", ward_duer, {0.292f, 0.244f, 0.146f}, {0.0238f, 0.0198f, 0.0133f}, 0.146f},
    {"delrin", blinn_phong, {0.299f, 0.249f, 0.15f}, {0.00755f, 0.00654f, 0.00461f}, 83.4f},
}};

/// The MERL name of a preset name or alias; empty when unknown.
std::string_view merl_name(std::string_view name) {
    if (name == "nickel") return "nickel";
    if (name == "acrylic-green" || name == "green-acrylic") return "green-acrylic";
    if (name == "delrin" || name == "derlin") return "delrin";
    return {};
}

vec3 merl_scaled(vec3 c) { return vec3(c.x, c.y * merl_green_scale, c.z * merl_blue_scale); }

}  // namespace

std::span<const BrdfFit> brdf_fits() { return fits; }

bool apply_brdf_preset(std::string_view name, Material& m, bool merl_colour) {
    const std::string_view material = merl_name(name);
    if (material.empty()) return false;
    for (const BrdfFit& fit : fits) {
        if (fit.material != material || fit.model != m.model) continue;
        m.c_d = merl_colour ? merl_scaled(fit.rho_d) : fit.rho_d;
        m.k_d = 1.0f;
        m.k_a = 0.0f;
        m.c_s = merl_colour ? merl_scaled(fit.rho_s) : fit.rho_s;
        m.k_s = 1.0f;
        if (fit.model == SpecularModel::blinn_phong)
            m.exponent = fit.lobe;
        else
            m.alpha = fit.lobe;
        return true;
    }
    return false;
}

std::vector<std::string> brdf_preset_names() { return {"nickel", "acrylic-green", "delrin"}; }

}  // namespace raylane
