// image: the film (linear float RGB), its encodings, and the PNG writer; PFM in image/pfm.h.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "core/pages.h"
#include "core/ray.h"

namespace raylane {

/// How linear values become 8-bit PNG values: sRGB transfer curve (the default for colour),
/// or linear (AOVs, and the report's look: no gamma).
enum class Encoding : uint8_t { srgb, linear };

struct Film {
    int width = 0, height = 0;
    std::vector<vec3, OverwriteAllocator<vec3>> pixels;  ///< row-major, row 0 at the top, linear
    vec3& at(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
    const vec3& at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

/// A black film.
Film make_film(int width, int height);

/// A film whose pixels are not written (their values are unspecified): for renderers that write
/// every pixel.
Film make_film_for_overwrite(int width, int height);

/// 8-bit value of a linear channel: clamped to [0, 1], optionally sRGB-encoded, rounded.
uint8_t encode_channel(float linear, Encoding encoding);

/// encode_channel(x, Encoding::srgb) for every float x, without its powf: the floats of [0, 1]
/// in buckets of 2^15 consecutive bit patterns (under 0.4 % of their value wide, so less than
/// half a step of the 8-bit curve: at most one step falls inside a bucket), the byte of each
/// bucket's first float, and the smallest float of each byte. 33 KB, built once by bisection
/// over encode_channel itself.
struct SrgbTable {
    static constexpr int shift = 15;
    static constexpr uint32_t one_bits = 0x3f800000u;  ///< the bits of 1.0f
    static constexpr uint32_t buckets = (one_bits >> shift) + 1;
    float step[257];        ///< step[k]: the smallest float encoded as k or more; step[256] = inf
    uint8_t base[buckets];  ///< the byte of the bucket's first float
    SrgbTable();
    uint8_t operator()(float linear) const {
        // clamped as encode_channel clamps, with -0 and NaN to +0 (their bits index no bucket)
        const float x =
            std::isfinite(linear) ? std::min(linear > 0.0f ? linear : 0.0f, 1.0f) : 0.0f;
        const uint8_t k = base[std::bit_cast<uint32_t>(x) >> shift];
        return static_cast<uint8_t>(k + (x >= step[k + 1]));
    }
};

/// The table, built on first use.
const SrgbTable& srgb_table();

/// 8-bit RGB bytes of an image, row by row.
using ImageBytes = std::vector<uint8_t, OverwriteAllocator<uint8_t>>;

/// The film's bytes: encode_channel on every channel (the rows in parallel).
ImageBytes encode_film(const Film& film, Encoding encoding);

/// Writes an 8-bit RGB PNG (stb_image_write). Written to a temporary file and renamed, so an
/// interrupted write never leaves a half image under `path`. Throws std::runtime_error.
void write_png(const std::string& path, const Film& film, Encoding encoding);

/// The PNG file write_png writes, in memory: stb_image_write's chunks and filters around the
/// zlib stream of image/deflate.h.
std::vector<uint8_t> encode_png(const Film& film, Encoding encoding);

/// The image formats write_image writes, named by the path's extension in any case (.png, .pfm,
/// .exr); none for any other.
enum class ImageFormat : uint8_t { none, png, pfm, exr };
ImageFormat image_format(const std::string& path);

/// Writes PNG (write_png), PFM (pfm.h, write_pfm) or EXR (exr.h, write_exr: the film as R, G, B
/// halves) by the file extension (image_format); throws for any other. `encoding` applies to
/// PNG only.
void write_image(const std::string& path, const Film& film, Encoding encoding);

/// The report's tone mapping (report-scenes.md 1.3): a pixel whose largest channel exceeds 1
/// is divided by it (hue kept); negative and NaN channels become 0. Write it linear (no gamma).
/// Takes the film by value: pass an rvalue to map it in place.
Film hue_preserving_clamp(Film film);

/// False colour for a cost in [0, 1]: dark blue, through green and yellow, to white.
vec3 false_colour(float x);

}  // namespace raylane
