// io: the JSON scene loader (load_scene.h; format: docs/scene-format.md): the top level of the
// scene format, the camera and the shading options, read strictly through io/json_reader.h;
// materials, lights and objects in load_scene_{materials,lights,objects}.cpp (io/scene_reader.h).
#include "io/load_scene.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "core/error.h"
#include "io/model_path.h"
#include "io/scene_reader.h"

namespace raylane {

SceneData SceneReader::read(const Json& root) {
    Node top{&root, "$"};
    expect_keys(top, {"version", "description", "camera", "background", "environment", "shading",
                      "tonemap", "materials", "objects", "lights"});
    SceneData scene;
    scene.source = file_;
    if (const Json* v = find(top, "version")) {
        Node n{v, member_path("$", "version")};
        int version = integer(n, 0, 1 << 30);
        if (version != 1) {
            fail(n, "unsupported version " + std::to_string(version) +
                        " (this loader reads version 1)");
        }
    }
    if (const Json* v = find(top, "description")) text(Node{v, "$.description"});
    scene.camera = read_camera(child(top, "camera"));
    scene.camera_path = read_camera_path(child(top, "camera"), scene.camera);
    scene.world_origin = world_origin_;
    if (const Json* v = find(top, "background")) {
        scene.background = color(Node{v, "$.background"});
    }
    if (const Json* v = find(top, "environment")) {
        scene.environment = read_texture(Node{v, "$.environment"}, scene);
    }
    if (const Json* v = find(top, "shading")) {
        scene.shading = read_shading(Node{v, "$.shading"});
    }
    if (const Json* v = find(top, "tonemap")) {
        scene.tonemap =
            choice(Node{v, "$.tonemap"}, {"srgb", "report"}) == 0 ? Tonemap::srgb : Tonemap::report;
    }
    if (const Json* v = find(top, "materials")) read_materials(Node{v, "$.materials"}, scene);
    if (const Json* v = find(top, "lights")) {
        Node lights{v, "$.lights"};
        expect(lights, lights.j->is_array(), "an array");
        for (size_t i = 0; i < v->size(); ++i) {
            scene.lights.push_back(read_light(Node{&(*v)[i], element_path(lights.path, i)}, scene));
        }
    }
    if (const Json* v = find(top, "objects")) {
        Node objects{v, "$.objects"};
        expect(objects, objects.j->is_array(), "an array");
        // how many objects name each mesh file (by its resolved path): the last of them
        // takes the loaded mesh (read_mesh), the others copy it; read_mesh reports the
        // names that do not resolve
        for (const Json& o : *v) {
            if (!o.is_object()) continue;
            const auto file = o.find("file");
            if (file == o.end() || !file->is_string()) continue;
            try {
                ++mesh_uses_[find_model(file->get<std::string>(), dir_)];
            } catch (const InputError&) {
            }
        }
        for (size_t i = 0; i < v->size(); ++i) {
            read_object(Node{&(*v)[i], element_path(objects.path, i)}, scene);
        }
    }
    return scene;
}

namespace {

/// The world point that becomes Raylane's origin (numerics.md section 17): the eye, so that
/// what the camera sees at a distance t has coordinates of about t and keeps the precision it
/// would have at home (a camera-relative origin), wherever the look-at point is. The scale is the
/// viewing distance, but at most one scene unit: a look-at point set far away may give the
/// direction of the view rather than the distance of its subject. An eye within 8 scales of the
/// world origin (in every coordinate) is not moved; farther out, the eye rounded to a multiple of
/// the power of two at or above the scale becomes the origin.
glm::dvec3 world_origin_for(glm::dvec3 position, glm::dvec3 look_at) {
    const double distance = glm::length(look_at - position);
    const glm::dvec3 a = glm::abs(position);
    if (!(distance > 0.0 && distance < std::numeric_limits<double>::infinity())) {
        return glm::dvec3(0.0);
    }
    const double scale = std::min(distance, 1.0);
    if (std::max({a.x, a.y, a.z}) <= 8.0 * scale) return glm::dvec3(0.0);
    const double grid = std::exp2(std::ceil(std::log2(scale)));
    return grid * glm::round(position / grid);
}

}  // namespace

Camera SceneReader::read_camera(const Node& n) {
    expect_keys(n, {"position", "look_at", "up", "fov_deg", "fov_axis", "resolution", "spp",
                    "lens_radius", "focal_distance", "path", "turntable"});
    Camera c;
    Node look = child(n, "look_at");
    world_origin_ = world_origin_for(dvec3(child(n, "position")), dvec3(look));
    c.position = point(child(n, "position"));
    c.look_at = point(look);
    if (const Json* v = find(n, "up")) c.up = direction(Node{v, member_path(n.path, "up")});
    Node fov = child(n, "fov_deg");
    c.fov_deg = real(fov);
    if (!(c.fov_deg > 0.0f && c.fov_deg < 180.0f)) {
        fail(fov, "must be between 0 and 180 (exclusive), got " + format_number(c.fov_deg));
    }
    if (const Json* v = find(n, "fov_axis")) {
        int axis = choice(Node{v, member_path(n.path, "fov_axis")}, {"vertical", "horizontal"});
        c.fov_axis = axis == 0 ? FovAxis::vertical : FovAxis::horizontal;
    }
    if (const Json* v = find(n, "resolution")) {
        Node res{v, member_path(n.path, "resolution")};
        expect(res, v->is_array() && v->size() == 2, "an array [width, height]");
        c.width = integer(Node{&(*v)[0], element_path(res.path, 0)}, 1, max_film_side);
        c.height = integer(Node{&(*v)[1], element_path(res.path, 1)}, 1, max_film_side);
        if (int64_t(c.width) * c.height > max_film_pixels)
            fail(res, "more than 2^28 pixels (" + std::to_string(c.width) + "x" +
                          std::to_string(c.height) + ")");
    }
    if (const Json* v = find(n, "spp")) {
        c.spp = integer(Node{v, member_path(n.path, "spp")}, 1, 1 << 20);
    }
    glm::dvec3 view = glm::dvec3(c.look_at) - glm::dvec3(c.position);
    if (!(glm::length(view) > 0.0)) fail(look, "must differ from the camera position");
    c.focal_distance = float(glm::length(view));
    if (const Json* v = find(n, "lens_radius")) {
        c.lens_radius = real(Node{v, member_path(n.path, "lens_radius")}, Sign::non_negative);
    }
    if (const Json* v = find(n, "focal_distance")) {
        c.focal_distance = real(Node{v, member_path(n.path, "focal_distance")}, Sign::positive);
    }
    glm::dvec3 side = glm::cross(glm::normalize(view), glm::normalize(glm::dvec3(c.up)));
    if (!(glm::length(side) > 1e-6)) {
        fail(find(n, "up") ? child(n, "up") : look, "the view direction is parallel to up");
    }
    return c;
}

CameraPath SceneReader::read_camera_path(const Node& camera, const Camera& still) const {
    CameraPath path;
    path.focus_at_look_at = find(camera, "focal_distance") == nullptr;
    const Json* keys_json = find(camera, "path");
    const Json* turn_json = find(camera, "turntable");
    if (keys_json && turn_json) {
        fail(Node{turn_json, member_path(camera.path, "turntable")},
             "a camera moves along a path or turns, not both");
    }
    if (turn_json) {
        Node t{turn_json, member_path(camera.path, "turntable")};
        expect(t, turn_json->is_object(), "an object");
        expect_keys(t, {"frames", "degrees"});
        path.turntable_frames = integer(child(t, "frames"), 1, 1 << 20);
        if (const Json* v = find(t, "degrees")) {
            path.turntable_degrees = real(Node{v, member_path(t.path, "degrees")});
        }
        return path;
    }
    if (!keys_json) return path;
    Node p{keys_json, member_path(camera.path, "path")};
    expect(p, keys_json->is_object(), "an object");
    expect_keys(p, {"keys", "fps", "interpolation"});
    if (const Json* v = find(p, "fps")) {
        path.fps = real(Node{v, member_path(p.path, "fps")}, Sign::positive);
    }
    if (const Json* v = find(p, "interpolation")) {
        path.interpolation =
            choice(Node{v, member_path(p.path, "interpolation")}, {"catmull-rom", "linear"}) == 0
                ? Interpolation::catmull_rom
                : Interpolation::linear;
    }
    Node keys = child(p, "keys");
    expect(keys, keys.j->is_array() && keys.j->size() >= 2, "an array of two or more keys");
    for (size_t i = 0; i < keys.j->size(); ++i) {
        Node k{&(*keys.j)[i], element_path(keys.path, i)};
        path.keys.push_back(read_camera_key(k, still));
        if (i > 0 && !(path.keys[i].time > path.keys[i - 1].time)) {
            fail(child(k, "time"), "must be later than the key before it");
        }
    }
    const double frames =
        (double(path.keys.back().time) - double(path.keys.front().time)) * double(path.fps);
    if (!(frames < double(1 << 20))) fail(p, "more than 2^20 frames");
    return path;
}

CameraKey SceneReader::read_camera_key(const Node& n, const Camera& still) const {
    expect(n, n.j->is_object(), "an object");
    expect_keys(n, {"time", "position", "look_at", "up", "fov_deg"});
    CameraKey k;
    k.time = real(child(n, "time"));
    k.position = point(child(n, "position"));
    Node look = child(n, "look_at");
    k.look_at = point(look);
    k.up = still.up;
    if (const Json* v = find(n, "up")) k.up = direction(Node{v, member_path(n.path, "up")});
    k.fov_deg = still.fov_deg;
    if (const Json* v = find(n, "fov_deg")) {
        Node fov{v, member_path(n.path, "fov_deg")};
        k.fov_deg = real(fov);
        if (!(k.fov_deg > 0.0f && k.fov_deg < 180.0f)) {
            fail(fov, "must be between 0 and 180 (exclusive), got " + format_number(k.fov_deg));
        }
    }
    const glm::dvec3 view = glm::dvec3(k.look_at) - glm::dvec3(k.position);
    if (!(glm::length(view) > 0.0)) fail(look, "must differ from the key's position");
    const glm::dvec3 side = glm::cross(glm::normalize(view), glm::normalize(glm::dvec3(k.up)));
    if (!(glm::length(side) > 1e-6)) fail(look, "the view direction is parallel to up");
    return k;
}

ShadingOptions SceneReader::read_shading(const Node& n) const {
    expect_keys(n, {"brdf", "max_reflection_depth", "max_refraction_depth", "local", "reflection",
                    "refraction", "fresnel", "reflected_color"});
    ShadingOptions o;
    if (const Json* v = find(n, "brdf")) {
        o.brdf = choice(Node{v, member_path(n.path, "brdf")}, {"physical", "report"}) == 0
                     ? BrdfScaling::physical
                     : BrdfScaling::report;
    }
    if (const Json* v = find(n, "max_reflection_depth")) {
        o.max_reflection_depth =
            integer(Node{v, member_path(n.path, "max_reflection_depth")}, 0, max_path_depth);
    }
    if (const Json* v = find(n, "max_refraction_depth")) {
        o.max_refraction_depth =
            integer(Node{v, member_path(n.path, "max_refraction_depth")}, 0, max_path_depth);
    }
    if (const Json* v = find(n, "local")) o.local = boolean(Node{v, member_path(n.path, "local")});
    if (const Json* v = find(n, "reflection")) {
        o.reflection = boolean(Node{v, member_path(n.path, "reflection")});
    }
    if (const Json* v = find(n, "refraction")) {
        o.refraction = boolean(Node{v, member_path(n.path, "refraction")});
    }
    if (const Json* v = find(n, "fresnel")) {
        o.fresnel = boolean(Node{v, member_path(n.path, "fresnel")});
    }
    if (const Json* v = find(n, "reflected_color")) {
        o.override_reflected = true;
        o.reflected_color = color(Node{v, member_path(n.path, "reflected_color")});
    }
    return o;
}

SceneData load_scene_from_string(std::string_view json, const std::string& path_for_errors,
                                 std::map<std::string, MeshData> loaded) {
    Json root = parse_json(json, path_for_errors, max_scene_json_depth);
    return SceneReader(path_for_errors, scene_dir(path_for_errors), std::move(loaded)).read(root);
}

std::string scene_dir(const std::string& scene_path) {
    const std::filesystem::path dir = std::filesystem::path(scene_path).parent_path();
    return dir.empty() ? std::string(".") : dir.string();
}

SceneData load_scene(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        throw InputError(path + ": cannot read: " + std::generic_category().message(EISDIR));
    }
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw InputError(
            path + ": cannot read: " + std::generic_category().message(errno ? errno : ENOENT));
    }
    // Read in blocks so that a huge file or an endless stream stops at the size limit.
    std::string text;
    std::vector<char> block(size_t{1} << 16);
    while (in.read(block.data(), std::streamsize(block.size())) || in.gcount() > 0) {
        text.append(block.data(), size_t(in.gcount()));
        if (text.size() > max_scene_file_bytes) {
            throw InputError(path + ": scene file larger than " +
                             std::to_string(max_scene_file_bytes >> 20) + " MiB");
        }
    }
    if (in.bad()) throw InputError(path + ": cannot read: I/O error");
    return load_scene_from_string(text, path);
}

}  // namespace raylane
