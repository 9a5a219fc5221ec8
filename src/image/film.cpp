// image: film encodings, the PNG writer, and write_image (PNG, PFM in pfm.h, EXR in exr.h).
#include "image/film.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "image/deflate.h"
#include "image/exr.h"
#include "image/pfm.h"
#include "image/write_file.h"

// stb_image_write writes the PNG's chunks; the zlib stream of its pixels is zlib_compress's
// (deflate.h), which stb_image_write frees with free(). No exception crosses stb: a failure
// returns null, which stbi_write_png_to_mem passes on (encode_png throws).
static unsigned char* raylane_png_zlib(unsigned char* data, int data_len, int* out_len,
                                       int /*quality*/) {
    try {
        const std::vector<uint8_t> z =
            raylane::zlib_compress({data, static_cast<size_t>(data_len)});
        auto* out = static_cast<unsigned char*>(std::malloc(z.size()));
        if (!out) return nullptr;
        std::memcpy(out, z.data(), z.size());
        *out_len = static_cast<int>(z.size());
        return out;
    } catch (...) {
        return nullptr;
    }
}

#define STBIW_ZLIB_COMPRESS raylane_png_zlib
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace raylane {

Film make_film(int width, int height) {
    Film f;
    f.width = width;
    f.height = height;
    f.pixels.assign(static_cast<size_t>(width) * static_cast<size_t>(height), vec3(0.0f));
    return f;
}

Film make_film_for_overwrite(int width, int height) {
    Film f;
    f.width = width;
    f.height = height;
    f.pixels.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
    return f;
}

uint8_t encode_channel(float linear, Encoding encoding) {
    float x = std::isfinite(linear) ? std::clamp(linear, 0.0f, 1.0f) : 0.0f;
    if (encoding == Encoding::srgb)
        x = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
    return static_cast<uint8_t>(x * 255.0f + 0.5f);  // x in [0, 1]: round half up
}

SrgbTable::SrgbTable() {
    // step[k], 1 <= k <= 255: by bisection over the bit patterns of [0, 1], which are ordered as
    // the floats are; encode_channel is non-decreasing (tests/image/film_test.cpp checks it)
    step[0] = 0.0f;
    step[256] = std::numeric_limits<float>::infinity();
    for (int k = 1; k <= 255; ++k) {
        uint32_t lo = 0, hi = one_bits;  // encode(lo) < k <= encode(hi)
        while (hi - lo > 1) {
            const uint32_t mid = lo + (hi - lo) / 2;
            (encode_channel(std::bit_cast<float>(mid), Encoding::srgb) >= k ? hi : lo) = mid;
        }
        step[k] = std::bit_cast<float>(hi);
    }
    int k = 0;
    for (uint32_t b = 0; b < buckets; ++b) {
        const float first = std::bit_cast<float>(b << shift);
        while (k < 255 && step[k + 1] <= first) ++k;
        base[b] = static_cast<uint8_t>(k);
    }
}

const SrgbTable& srgb_table() {
    static const SrgbTable table;
    return table;
}

ImageBytes encode_film(const Film& film, Encoding encoding) {
    ImageBytes bytes(film.pixels.size() * 3);
    if (bytes.empty()) return bytes;
    const SrgbTable& srgb = srgb_table();
    tbb::parallel_for(tbb::blocked_range<int>(0, film.height),
                      [&](const tbb::blocked_range<int>& r) {
                          for (int y = r.begin(); y < r.end(); ++y) {
                              const vec3* in = &film.at(0, y);
                              uint8_t* out = bytes.data() + size_t(y) * size_t(film.width) * 3;
                              for (int x = 0; x < film.width; ++x)
                                  for (int c = 0; c < 3; ++c)
                                      out[3 * x + c] = encoding == Encoding::srgb
                                                           ? srgb(in[x][c])
                                                           : encode_channel(in[x][c], encoding);
                          }
                      });
    return bytes;
}

std::vector<uint8_t> encode_png(const Film& film, Encoding encoding) {
    const ImageBytes bytes = encode_film(film, encoding);
    int size = 0;
    unsigned char* png =
        stbi_write_png_to_mem(bytes.data(), film.width * 3, film.width, film.height, 3, &size);
    // stb_image_write and zlib_compress fail only when an allocation does
    if (!png) throw std::runtime_error("cannot encode the PNG: out of memory");
    std::vector<uint8_t> out(png, png + size);
    std::free(png);
    return out;
}

void write_png(const std::string& path, const Film& film, Encoding encoding) {
    std::vector<uint8_t> png;
    try {
        png = encode_png(film, encoding);
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
    image_detail::write_file(path, [&](std::FILE* f) {
        return std::fwrite(png.data(), 1, png.size(), f) == png.size();
    });
}

ImageFormat image_format(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".png"   ? ImageFormat::png
           : ext == ".pfm" ? ImageFormat::pfm
           : ext == ".exr" ? ImageFormat::exr
                           : ImageFormat::none;
}

void write_image(const std::string& path, const Film& film, Encoding encoding) {
    switch (image_format(path)) {
        case ImageFormat::pfm:
            write_pfm(path, film);
            return;
        case ImageFormat::png:
            write_png(path, film, encoding);
            return;
        case ImageFormat::exr: {
            ExrImage image = make_exr_image(film.width, film.height);
            image.layers.push_back({"", {"R", "G", "B"}, film});
            write_exr(path, image);
            return;
        }
        case ImageFormat::none:
            break;
    }
    throw std::runtime_error(path + ": unknown image extension (use .png, .pfm or .exr)");
}

vec3 false_colour(float x) {
    x = std::isfinite(x) ? std::clamp(x, 0.0f, 1.0f) : 1.0f;
    // piecewise-linear ramp through five stops
    static const vec3 stops[5] = {{0.0f, 0.0f, 0.25f},
                                  {0.0f, 0.35f, 0.9f},
                                  {0.1f, 0.8f, 0.2f},
                                  {1.0f, 0.85f, 0.0f},
                                  {1.0f, 1.0f, 1.0f}};
    const float s = x * 4.0f;
    const int i = std::min(3, static_cast<int>(s));
    const float f = s - static_cast<float>(i);
    return stops[i] * (1.0f - f) + stops[i + 1] * f;
}

Film hue_preserving_clamp(Film film) {
    for (vec3& c : film.pixels) {
        for (int k = 0; k < 3; ++k) c[k] = c[k] > 0.0f ? c[k] : 0.0f;  // NaN too
        const float m = std::max(c.x, std::max(c.y, c.z));
        if (m > 1.0f) c /= m;
    }
    return film;
}

}  // namespace raylane
