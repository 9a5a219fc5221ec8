// image: the PFM format (linear float RGB, little-endian, bottom row first): the writer of
// `raylane render -o FILE.pfm` and of the report's references, and the reader of the latter.
#pragma once

#include <optional>
#include <string>

#include "image/film.h"

namespace raylane {

/// Writes a little-endian linear float PFM (bottom row first, as the format says): "PF", width,
/// height, scale -1.0, then the floats. Written to a temporary file and renamed, so an
/// interrupted write never leaves a half image under `path`. Throws std::runtime_error.
void write_pfm(const std::string& path, const Film& film);

/// A PFM as write_pfm writes it ("PF", width, height, negative scale, little-endian floats,
/// bottom row first) of exactly width x height pixels; nullopt when anything differs, when the
/// file is missing or cannot be read.
std::optional<Film> read_pfm(const std::string& path, int width, int height);

}  // namespace raylane
