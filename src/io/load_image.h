// io: image files (PNG, JPEG, Radiance HDR through stb_image) -> scene/scene.h Texture, and the
// procedural checker. Looked up by shade/texture_scalar.h and shade/texture_packet.h.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "scene/scene.h"

namespace raylane {

/// How the 8-bit (or 16-bit) values of an LDR file become linear texels: `linear` = value / max
/// (the report's rule, report-scenes.md 1.6), `srgb` = the sRGB transfer function decoded
/// (IEC 61966-2-1). Radiance HDR files are already linear and ignore it.
enum class ImageEncoding : uint8_t { linear, srgb };

/// Largest image accepted: each side at most max_image_side and width * height at most
/// max_image_texels (8192 x 8192). Checked on the header, before anything is decoded.
inline constexpr int max_image_side = 32768;
inline constexpr int64_t max_image_texels = int64_t{1} << 26;
/// Largest file read (bytes); bigger files are rejected before they are read.
inline constexpr int64_t max_image_file_bytes = int64_t{1} << 29;

/// Reads a PNG, JPEG or Radiance HDR file into an image Texture: RGB floats, row 0 = the top
/// row of the file, `source` = path, filter and wrap left at the Texture defaults. Grey, grey +
/// alpha, RGB and RGBA inputs all give RGB (grey replicated, alpha dropped, not premultiplied);
/// 16-bit PNGs keep 16 bits (value / 65535).
///
/// Errors (InputError, one line "path: reason"): missing or unreadable file, a directory or
/// other non-regular file, a file over max_image_file_bytes, an empty file, a file that is not
/// one of the three formats, zero or negative size, a size over the limits above (rejected
/// from the header alone, so a hostile header never allocates), a truncated or corrupt file.
/// Decoder allocations are capped by a budget derived from the header's size.
Texture load_texture(const std::string& path, ImageEncoding encoding = ImageEncoding::linear);

/// Same as load_texture on bytes already in memory; `name_for_errors` prefixes messages and
/// becomes the texture's `source`.
Texture load_texture_from_memory(std::string_view bytes, const std::string& name_for_errors,
                                 ImageEncoding encoding = ImageEncoding::linear);

/// The procedural checkerboard: color_a where floor(u checks) + floor(v checks) is even,
/// color_b elsewhere (shade/texture_scalar.h). `source` = "checker".
Texture make_checker(vec3 a, vec3 b, float checks);

/// The sRGB transfer function decoded: c / 12.92 for c <= 0.04045, else ((c + 0.055) / 1.055)^2.4
/// (c in [0, 1], computed in double).
float srgb_to_linear(float c);

}  // namespace raylane
