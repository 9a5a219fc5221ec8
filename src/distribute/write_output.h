// distribute: a render's films to the output file, the one way `render` and `assemble` write them.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "image/exr.h"
#include "image/film.h"
#include "render/render_params.h"
#include "scene/scene.h"

namespace raylane {

/// A raw render result (RenderResult::film) and what it shows.
struct AovFilm {
    Aov aov = Aov::color;
    Film film;
};

struct OutputOptions {
    Tonemap tonemap = Tonemap::srgb;  ///< the scene's: how colour becomes a PNG
    int threads = 0;                  ///< threads encoding a PNG; 0 = all
    bool exr_float = false;           ///< EXR channels as 32-bit floats, not 16-bit halves
    /// EXR string attributes (part.h, frame_attributes); PNG and PFM have none.
    std::vector<std::pair<std::string, std::string>> attributes;
};

/// The EXR layer of an AOV: colour as R, G, B; normal as normal.X, normal.Y, normal.Z; depth as
/// depth.Z; BVH cost as bvh_cost.Y.
ExrLayer exr_layer(Aov aov, Film film);

/// The AOV whose layer exr_layer names `name` ("" for colour); false for any other name.
bool aov_of_exr_layer(const std::string& name, Aov& aov);

/// Writes raw films by the path's extension. PNG: colour sRGB-encoded, or by the report's
/// hue-preserving clamp (linear) under Tonemap::report; an AOV as visualise_aov maps it. PFM:
/// the raw values. EXR: the raw values, one layer per film (exr_layer). PNG and PFM take one
/// film (else std::invalid_argument). Returns the scale a PNG of an AOV used (visualise_aov),
/// else "". Throws std::runtime_error when the file cannot be written.
std::string write_render_output(const std::string& path, std::vector<AovFilm> films,
                                const OutputOptions& options);

/// write_render_output of one film.
std::string write_render_output(const std::string& path, Film film, Aov aov,
                                const OutputOptions& options);

}  // namespace raylane
