// examples/render_scene: a scene rendered with raylane::Scene to a float image and written as a
// binary PPM (8-bit: clamped to [0, 1] and sRGB-encoded) or PFM (the floats as they are), by
// hand, with no image library.
//
//   render_scene [SCENE [OUTPUT [WIDTH]]]
//
// SCENE is a JSON scene or an OBJ or PLY model (a model is rendered as its own scene: on a
// floor, framed by a camera, lit), or "" for the built-in scene; the default is bunny.ply from a
// folder on RAYLANE_MODEL_PATH. OUTPUT ends in .ppm or .pfm (default render_scene.ppm). WIDTH
// is in pixels (default 640; 0 keeps the scene's own); the height keeps the scene's aspect
// ratio. Exits 0, or 1 with Raylane's one-line message when the scene cannot be read or a
// setting is refused.
#include <raylane/raylane.h>  // the whole library: Scene, Mesh, instruction sets, Error

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// An 8-bit value of a linear channel: clamped to [0, 1] (NaN to 0), then the sRGB curve.
uint8_t srgb_byte(float linear) {
    const float x = std::isfinite(linear) ? std::clamp(linear, 0.0f, 1.0f) : 0.0f;
    const float encoded = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1 / 2.4f) - 0.055f;
    return static_cast<uint8_t>(std::lround(255.0f * encoded));
}

/// Binary PPM (P6): a text header, then R, G, B bytes, row 0 (the top) first.
bool write_ppm(const std::string& path, const raylane::Image& image) {
    std::ofstream out(path, std::ios::binary);
    out << "P6\n" << image.width << ' ' << image.height << "\n255\n";
    std::vector<char> bytes(image.pixels.size());
    for (size_t i = 0; i < image.pixels.size(); ++i)
        bytes[i] = static_cast<char>(srgb_byte(image.pixels[i]));
    out.write(bytes.data(), std::streamsize(bytes.size()));
    return bool(out);
}

/// PFM: "PF" (3 channels) or "Pf" (1), the size, -1.0 for little-endian floats (x86-64's own
/// order), then the rows from the bottom one up: the file `raylane render -o FILE.pfm` writes.
bool write_pfm(const std::string& path, const raylane::Image& image) {
    std::ofstream out(path, std::ios::binary);
    out << (image.channels == 3 ? "PF" : "Pf") << '\n'
        << image.width << ' ' << image.height << "\n-1.0\n";
    const size_t row_floats = size_t(image.width) * size_t(image.channels);
    for (int y = image.height - 1; y >= 0; --y)
        out.write(reinterpret_cast<const char*>(&image.pixels[size_t(y) * row_floats]),
                  std::streamsize(row_floats * sizeof(float)));
    return bool(out);
}

}  // namespace

int main(int argc, char** argv) {
    const std::string output = argc > 2 ? argv[2] : "render_scene.ppm";
    if (!ends_with(output, ".ppm") && !ends_with(output, ".pfm")) {
        std::fprintf(stderr, "render_scene: %s: the output must end in .ppm or .pfm\n",
                     output.c_str());
        return 1;
    }
    try {
        // Loading reads the file and builds the BVHs once; every render reuses them. A model
        // file becomes its own scene, and "" is the built-in scene. Scene::load takes a path;
        // find_model finds the default model's file on RAYLANE_MODEL_PATH. (The models a JSON
        // scene names are looked up beside the scene, then on RAYLANE_MODEL_PATH.)
        const std::string path = argc > 1 ? argv[1] : raylane::find_model("bunny.ply");
        const raylane::Scene scene = raylane::Scene::load(path);
        for (const std::string& warning : scene.warnings())
            std::fprintf(stderr, "render_scene: %s\n", warning.c_str());

        // 0 in a setting keeps the scene's own value: its samples per pixel, all threads,
        // and here its aspect ratio, as only the width is given.
        raylane::RenderSettings settings;
        settings.width = argc > 3 ? std::atoi(argv[3]) : 640;
        settings.path = raylane::TracePath::packet;  // the default: SIMD packets, W rays at once
        settings.image = raylane::ImageKind::color;  // linear RGB; depth, normal, bvh_cost too

        const auto start = std::chrono::steady_clock::now();
        const raylane::Image image = scene.render(settings);  // throws Error for a bad setting
        const std::chrono::duration<double, std::milli> took =
            std::chrono::steady_clock::now() - start;

        const bool written =
            ends_with(output, ".pfm") ? write_pfm(output, image) : write_ppm(output, image);
        if (!written) {
            std::fprintf(stderr, "render_scene: %s: cannot write the file\n", output.c_str());
            return 1;
        }
        std::printf("%s: %d x %d pixels at %d samples per pixel, rendered in %.0f ms\n",
                    scene.source().c_str(), image.width, image.height, scene.spp(), took.count());
        std::printf("instruction set: %s (%d rays per packet); wrote %s\n",
                    raylane::instruction_set().c_str(), raylane::packet_width(), output.c_str());
        return 0;
    } catch (const raylane::Error& e) {  // e.g. "no/such.json: no such file"
        std::fprintf(stderr, "render_scene: %s\n", e.what());
        return 1;
    }
}
