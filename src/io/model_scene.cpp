// io: a model file as a scene of its own (model_scene.h).
#include "io/model_scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>

#include "core/error.h"
#include "io/load_mesh.h"
#include "io/load_scene.h"
#include "io/model_path.h"
#include "scene/transform.h"

namespace raylane {

namespace {

/// The camera's view: this far to the right of the model's front (+z) and this far above it.
constexpr double view_azimuth_deg = 35.0, view_elevation_deg = 20.0;
/// Vertical field of view; the bounding sphere fills it.
constexpr double view_fov_deg = 40.0;

/// A number as JSON: the shortest form that reads back to the same float.
std::string num(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", x);
    return buf;
}

std::string vec(glm::dvec3 v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "[%.9g, %.9g, %.9g]", v.x, v.y, v.z);
    return buf;
}

/// A JSON string literal of `s` (quotes, backslashes and control characters escaped).
std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += char(c);
        } else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
        } else {
            out += char(c);
        }
    }
    return out + "\"";
}

/// A point at `distance` from `target` in the direction of azimuth and elevation (degrees;
/// azimuth from +z towards +x).
glm::dvec3 orbit(glm::dvec3 target, double azimuth_deg, double elevation_deg, double distance) {
    const double az = azimuth_deg * std::numbers::pi / 180.0,
                 el = elevation_deg * std::numbers::pi / 180.0;
    return target + distance * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el),
                                          std::cos(az) * std::cos(el));
}

}  // namespace

bool is_model_file(const std::string& path) {
    const std::string ext = mesh_extension(path);
    return ext == ".obj" || ext == ".ply" || ext == ".obj.gz" || ext == ".ply.gz";
}

std::string model_scene_json(const std::string& file, const Aabb& bounds) {
    const glm::dvec3 e = glm::dvec3(bounds.extent());
    const double radius = 0.5 * glm::length(e);
    if (bounds.empty() || !(radius > 0.0) || !std::isfinite(radius))
        throw InputError(file + ": the model has no extent to frame");
    // after the fit: the bottom centre at the origin, the box's centre above it
    const glm::dvec3 centre(0.0, 0.5 * e.y, 0.0);
    const double distance = 0.9 * radius / std::sin(0.5 * view_fov_deg * std::numbers::pi / 180.0);
    const glm::dvec3 eye = orbit(centre, view_azimuth_deg, view_elevation_deg, distance);
    // key light above left of the camera, fill light low on the right
    const double key_d = 2.5 * radius + distance * 0.5, fill_d = 3.0 * radius;
    const glm::dvec3 key = orbit(centre, -40.0, 50.0, key_d);
    const glm::dvec3 fill = orbit(centre, 80.0, 15.0, fill_d);
    std::string j;
    auto add = [&j](const auto&... parts) { (j.append(parts), ...); };
    add("{\n  \"version\": 1,\n  \"description\": ",
        quoted("The model " + file +
               " alone, in its own units with +y up: its bottom centre at the origin on a "
               "floor, a camera at a three-quarter view, a key and a fill light with shadows."),
        ",\n");
    add("  \"camera\": {\"position\": ", vec(eye), ", \"look_at\": ", vec(centre),
        ", \"up\": [0, 1, 0],\n             \"fov_deg\": ", num(view_fov_deg),
        ", \"resolution\": [1280, 720], \"spp\": 4},\n");
    add("  \"background\": [0.02, 0.02, 0.03],\n  \"materials\": {\n",
        "    \"floor\": {\"c_d\": [0.6, 0.6, 0.6], \"k_d\": 0.7, \"k_a\": 0.08},\n",
        "    \"default\": {\"c_d\": [0.8, 0.78, 0.74], \"k_d\": 0.6, \"k_a\": 0.08, ",
        "\"c_s\": [1, 1, 1], \"k_s\": 0.25, \"exponent\": 40}\n  },\n");
    add("  \"objects\": [\n    {\"shape\": \"plane\", \"point\": [0, 0, 0], ",
        "\"normal\": [0, 1, 0], \"material\": \"floor\"},\n",
        "    {\"shape\": \"mesh\", \"file\": ", quoted(file), ", \"fit\": {\"scale\": 1}}\n  ],\n");
    add("  \"lights\": [\n    {\"type\": \"point\", \"position\": ", vec(key),
        ", \"color\": [1, 0.95, 0.88], \"intensity\": ", num(0.9 * key_d * key_d),
        ", \"shadows\": true},\n");
    add("    {\"type\": \"point\", \"position\": ", vec(fill),
        ", \"color\": [0.75, 0.82, 1], \"intensity\": ", num(0.35 * fill_d * fill_d),
        ", \"shadows\": true}\n  ]\n}\n");
    return j;
}

SceneData load_model_scene(const std::string& path) {
    const std::string dir = scene_dir(path);
    const std::string file = std::filesystem::path(path).filename().string();
    const std::string resolved = find_model(file, dir);
    MeshData mesh = load_mesh(resolved);
    const std::string json = model_scene_json(file, mesh_bounds(mesh));
    std::map<std::string, MeshData> loaded;
    loaded.emplace(resolved, std::move(mesh));
    return load_scene_from_string(json, path, std::move(loaded));
}

}  // namespace raylane
