// image: the film (linear float RGB), its encodings, and the PNG / PFM writers.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/ray.h"

namespace raylane {

/// How linear values become 8-bit PNG values: sRGB transfer curve (the default for colour),
/// or linear (AOVs, and the report's look: no gamma).
enum class Encoding : uint8_t { srgb, linear };

/// std::allocator whose value-initialising construct() default-initialises instead: a vector
/// of floats grown by resize() is left unwritten (a 1080p film is 25 MB that the renderers
/// overwrite anyway). Everything else is std::allocator's.
template <class T>
struct OverwriteAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = OverwriteAllocator<U>;
    };
    OverwriteAllocator() = default;
    template <class U>
    OverwriteAllocator(const OverwriteAllocator<U>&) noexcept {}
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

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

/// Writes an 8-bit RGB PNG (stb_image_write). Written to a temporary file and renamed, so an
/// interrupted write never leaves a half image under `path`. Throws std::runtime_error.
void write_png(const std::string& path, const Film& film, Encoding encoding);

/// Writes a little-endian linear float PFM (bottom row first, as the format says).
void write_pfm(const std::string& path, const Film& film);

/// Writes PNG or PFM by the file extension (.png, .pfm).
void write_image(const std::string& path, const Film& film, Encoding encoding);

/// The report's tone mapping (report-scenes.md 1.3): a pixel whose largest channel exceeds 1
/// is divided by it (hue kept); negative and NaN channels become 0. Write it linear (no gamma).
Film hue_preserving_clamp(const Film& film);

/// False colour for a cost in [0, 1]: dark blue, through green and yellow, to white.
vec3 false_colour(float x);

}  // namespace raylane
