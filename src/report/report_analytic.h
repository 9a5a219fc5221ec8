// report: the analytic references (error-vs-time.md, "Analytic references"): images computed
// from the scene's formulas rather than rendered, for the scenes simple enough to have one.
#pragma once

#include <optional>
#include <string>

#include "image/film.h"
#include "scene/scene.h"

namespace raylane {

/// Built-in analytic references, tried in order:
///  * "lit sphere": one untransformed sphere with a plain Phong material (no texture,
///    mirror, glass, emission or normal map), lit by point lights outside it and directional
///    lights, seen by a pinhole camera outside it, background colour elsewhere. Each pixel is the
///    mean over a supersampling x supersampling grid of its footprint, evaluated in double with the
///    formula of shade/shade_scalar.h: k_a c_d + sum k_d F c c_d cos(theta) + k_s F c c_s
///    max(cos(alpha), 0)^e. A convex sphere never shadows its own lit side.
///  * "mirror furnace" (the Whitted form of the furnace test): one convex object (sphere, box,
///    cylinder) whose material is a perfect angle-independent mirror (reflection 1, fresnel off,
///    c_s 1, k_a_after 0, so that (1 - R) local adds nothing), no environment map: every pixel
///    equals the background.
/// The white-Lambertian furnace needs diffuse surfaces lit by the environment, which the Whitted
/// renderer does not compute; it has no entry. A new case is one more function in
/// report_analytic.cpp.
struct AnalyticReference {
    std::string name;
    Film film;
};
std::optional<AnalyticReference> analytic_reference(const SceneData& scene, int supersampling = 64);

}  // namespace raylane
