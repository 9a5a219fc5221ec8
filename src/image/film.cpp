// image: film encodings and writers.
#include "image/film.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO_UNUSED
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

namespace {

/// Renames `tmp` over `path`, or removes it and throws.
void commit_file(const std::string& tmp, const std::string& path) {
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw std::runtime_error(path + ": cannot write: " + ec.message());
    }
}

std::string temp_name(const std::string& path) { return path + ".partial"; }

}  // namespace

void write_png(const std::string& path, const Film& film, Encoding encoding) {
    std::vector<uint8_t> bytes(film.pixels.size() * 3);
    for (size_t i = 0; i < film.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) bytes[3 * i + c] = encode_channel(film.pixels[i][c], encoding);
    const std::string tmp = temp_name(path);
    stbi_write_png_compression_level = 4;  // stb's default (8) costs more than the render
    if (!stbi_write_png(tmp.c_str(), film.width, film.height, 3, bytes.data(), film.width * 3))
        throw std::runtime_error(path + ": cannot write PNG");
    commit_file(tmp, path);
}

void write_pfm(const std::string& path, const Film& film) {
    const std::string tmp = temp_name(path);
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw std::runtime_error(path + ": cannot open for writing");
    std::fprintf(f, "PF\n%d %d\n-1.0\n", film.width, film.height);
    bool ok = true;
    for (int y = film.height - 1; y >= 0 && ok; --y)
        ok = std::fwrite(&film.at(0, y), sizeof(vec3), static_cast<size_t>(film.width), f) ==
             static_cast<size_t>(film.width);
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) {
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": write failed");
    }
    commit_file(tmp, path);
}

void write_image(const std::string& path, const Film& film, Encoding encoding) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".pfm")
        write_pfm(path, film);
    else if (ext == ".png")
        write_png(path, film, encoding);
    else
        throw std::runtime_error(path + ": unknown image extension (use .png or .pfm)");
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

Film hue_preserving_clamp(const Film& film) {
    Film out = film;
    for (vec3& c : out.pixels) {
        for (int k = 0; k < 3; ++k) c[k] = c[k] > 0.0f ? c[k] : 0.0f;  // NaN too
        const float m = std::max(c.x, std::max(c.y, c.z));
        if (m > 1.0f) c /= m;
    }
    return out;
}

}  // namespace raylane
