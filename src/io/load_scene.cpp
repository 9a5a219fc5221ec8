// io: the JSON scene loader (load_scene.h; format: docs/scene-format.md): the scene format, read
// strictly through io/json_reader.h (parsing with a depth limit and no duplicate keys, typed
// reads whose errors name the JSON path).
#include "io/load_scene.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/error.h"
#include "io/json_reader.h"
#include "io/load_image.h"
#include "io/load_mesh.h"
#include "io/model_path.h"
#include "scene/brdf_presets.h"
#include "scene/mesh_normals.h"
#include "scene/transform.h"

namespace raylane {

namespace {

using Node = JsonNode;

/// The scene format on top of JsonReader's strict typed reads (every error names the JSON path).
class SceneReader : JsonReader {
  public:
    SceneReader(std::string file, std::string dir)
        : JsonReader(std::move(file)), dir_(std::move(dir)) {}

    Scene read(const Json& root) {
        Node top{&root, "$"};
        expect_keys(top, {"version", "description", "camera", "background", "environment",
                          "shading", "tonemap", "materials", "objects", "lights"});
        Scene scene;
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
            scene.tonemap = choice(Node{v, "$.tonemap"}, {"srgb", "report"}) == 0 ? Tonemap::srgb
                                                                                  : Tonemap::report;
        }
        if (const Json* v = find(top, "materials")) read_materials(Node{v, "$.materials"}, scene);
        if (const Json* v = find(top, "lights")) {
            Node lights{v, "$.lights"};
            expect(lights, lights.j->is_array(), "an array");
            for (size_t i = 0; i < v->size(); ++i) {
                scene.lights.push_back(
                    read_light(Node{&(*v)[i], element_path(lights.path, i)}, scene));
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

  private:
    std::string dir_;
    glm::dvec3 world_origin_{0.0};  ///< the world point stored as (0, 0, 0); set by read_camera

    /// The world point that becomes Raylane's origin (numerics.md section 17). A scene that looks
    /// at a point within 8 viewing distances of the world origin is not moved. Farther out, the
    /// look-at point rounded to a multiple of the power of two at or above the viewing distance
    /// becomes the origin, so that the subject's coordinates are no larger than the view and
    /// keep the precision they would have at home.
    static glm::dvec3 world_origin_for(glm::dvec3 position, glm::dvec3 look_at) {
        const double distance = glm::length(look_at - position);
        const glm::dvec3 a = glm::abs(look_at);
        if (!(distance > 0.0 && distance < std::numeric_limits<double>::infinity()) ||
            std::max({a.x, a.y, a.z}) <= 8.0 * distance)
            return glm::dvec3(0.0);
        const double grid = std::exp2(std::ceil(std::log2(distance)));
        return grid * glm::round(look_at / grid);
    }
    std::map<std::string, Mesh> meshes_;  ///< loaded meshes by resolved path, before baking, until
                                          ///< their last object takes them
    std::map<std::string, int> mesh_uses_;     ///< objects still to read, by resolved path
    std::map<std::string, int32_t> textures_;  ///< texture index by file and options
    /// Material index by name, the first material of a name (objects name their material; a
    /// search of the list made 100,000 objects of 100,000 materials quadratic).
    std::unordered_map<std::string, uint32_t> material_ids_;

    uint32_t add_material(Scene& scene, Material m) {
        const uint32_t index = uint32_t(scene.materials.size());
        material_ids_.emplace(m.name, index);
        scene.materials.push_back(std::move(m));
        return index;
    }

    /// A world-space point, moved so that world_origin_ becomes Raylane's origin (in double,
    /// rounded to float once).
    vec3 point(const Node& n) const { return vec3(dvec3(n) - world_origin_); }

    Camera read_camera(const Node& n) {
        expect_keys(n, {"position", "look_at", "up", "fov_deg", "fov_axis", "resolution", "spp",
                        "lens_radius", "focal_distance"});
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

    /// A texture given as a file name, {"file", "filter", "encoding", "repeat"} or
    /// {"checker": [colour a, colour b], "checks"}; loaded once per file and options.
    int32_t read_texture(const Node& n, Scene& scene) {
        Texture options;
        ImageEncoding encoding = ImageEncoding::linear;
        std::string file;
        if (n.j->is_string()) {
            file = text(n);
        } else {
            expect_keys(n, {"file", "filter", "encoding", "repeat", "checker", "checks"});
            if (const Json* v = find(n, "checker")) {
                if (find(n, "file"))
                    fail(child(n, "file"), "give either file or checker, not both");
                Node c{v, member_path(n.path, "checker")};
                expect(c, v->is_array() && v->size() == 2, "an array of two colours");
                float checks = 8.0f;
                if (const Json* k = find(n, "checks")) {
                    checks = real(Node{k, member_path(n.path, "checks")}, Sign::positive);
                }
                scene.textures.push_back(
                    make_checker(color(Node{&(*v)[0], element_path(c.path, 0)}),
                                 color(Node{&(*v)[1], element_path(c.path, 1)}), checks));
                return int32_t(scene.textures.size() - 1);
            }
            if (find(n, "checks")) fail(child(n, "checks"), "only goes with \"checker\"");
            file = text(child(n, "file"));
            if (const Json* v = find(n, "filter")) {
                options.filter =
                    choice(Node{v, member_path(n.path, "filter")}, {"bilinear", "nearest"}) == 0
                        ? TextureFilter::bilinear
                        : TextureFilter::nearest;
            }
            if (const Json* v = find(n, "encoding")) {
                encoding = choice(Node{v, member_path(n.path, "encoding")}, {"linear", "srgb"}) == 0
                               ? ImageEncoding::linear
                               : ImageEncoding::srgb;
            }
            if (const Json* v = find(n, "repeat")) {
                options.repeat = boolean(Node{v, member_path(n.path, "repeat")});
            }
        }
        Node file_node = n.j->is_string() ? n : child(n, "file");
        std::string resolved;
        try {
            resolved = find_model(file, dir_, ModelKind::texture);
        } catch (const InputError& e) {
            fail(file_node, e.what());
        }
        const std::string key = resolved + (encoding == ImageEncoding::srgb ? "|srgb" : "|lin") +
                                (options.filter == TextureFilter::nearest ? "|n" : "|b") +
                                (options.repeat ? "|r" : "|c");
        if (auto it = textures_.find(key); it != textures_.end()) return it->second;
        Texture t;
        try {
            t = load_texture(resolved, encoding);
        } catch (const InputError& e) {
            fail(file_node, e.what());
        }
        t.filter = options.filter;
        t.repeat = options.repeat;
        scene.textures.push_back(std::move(t));
        textures_[key] = int32_t(scene.textures.size() - 1);
        return textures_[key];
    }

    ShadingOptions read_shading(const Node& n) const {
        expect_keys(n, {"brdf", "max_reflection_depth", "max_refraction_depth", "local",
                        "reflection", "refraction", "fresnel", "reflected_color"});
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
        if (const Json* v = find(n, "local"))
            o.local = boolean(Node{v, member_path(n.path, "local")});
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

    void read_materials(const Node& n, Scene& scene) {
        expect(n, n.j->is_object(), "an object");
        for (auto it = n.j->begin(); it != n.j->end(); ++it) {
            Node m{&it.value(), member_path(n.path, it.key())};
            if (it.key().empty()) fail(m, "a material name must not be empty");
            add_material(scene, read_material(m, it.key(), scene));
        }
    }

    Material read_material(const Node& m, const std::string& name, Scene& scene) {
        expect_keys(m, {"model",
                        "preset",
                        "merl_colour",
                        "c_d",
                        "k_d",
                        "k_a",
                        "c_s",
                        "k_s",
                        "exponent",
                        "alpha",
                        "glossy_samples",
                        "texture",
                        "texture_specular",
                        "reflection",
                        "k_a_after",
                        "fresnel",
                        "refraction",
                        "env_map",
                        "normal_map",
                        "normal_map_mode",
                        "emission"});
        Material mat;
        mat.name = name;
        auto path = [&](std::string_view key) { return member_path(m.path, key); };
        if (const Json* v = find(m, "model")) {
            constexpr SpecularModel models[] = {SpecularModel::phong, SpecularModel::glossy_phong,
                                                SpecularModel::blinn_phong, SpecularModel::ward,
                                                SpecularModel::ward_duer};
            mat.model =
                models[choice(Node{v, path("model")},
                              {"phong", "glossy-phong", "blinn-phong", "ward", "ward-duer"})];
        }
        if (const Json* v = find(m, "preset")) {
            Node p{v, path("preset")};
            bool merl = false;
            if (const Json* c = find(m, "merl_colour"))
                merl = boolean(Node{c, path("merl_colour")});
            if (!apply_brdf_preset(text(p), mat, merl)) {
                std::vector<std::string> names = brdf_preset_names();
                fail(p, "no fitted " + json_quoted(text(p)) +
                            " for this model (presets exist for ward, ward-duer and blinn-phong: " +
                            join(names, names.size()) + ")");
            }
        } else if (find(m, "merl_colour")) {
            fail(child(m, "merl_colour"), "only goes with \"preset\"");
        }
        if (const Json* v = find(m, "c_d")) mat.c_d = color(Node{v, path("c_d")});
        if (const Json* v = find(m, "k_d"))
            mat.k_d = real(Node{v, path("k_d")}, Sign::non_negative);
        if (const Json* v = find(m, "k_a"))
            mat.k_a = real(Node{v, path("k_a")}, Sign::non_negative);
        if (const Json* v = find(m, "c_s")) mat.c_s = color(Node{v, path("c_s")});
        if (const Json* v = find(m, "k_s"))
            mat.k_s = real(Node{v, path("k_s")}, Sign::non_negative);
        if (const Json* v = find(m, "exponent")) {
            Node e{v, path("exponent")};
            mat.exponent = real(e, Sign::non_negative);
            if (mat.exponent > 1e7f) fail(e, "must be at most 1e7");
        }
        if (const Json* v = find(m, "alpha")) {
            Node a{v, path("alpha")};
            mat.alpha = real(a, Sign::positive);
            if (mat.alpha < 1e-4f || mat.alpha > 1.0f) fail(a, "must be from 1e-4 to 1");
        }
        if (const Json* v = find(m, "glossy_samples")) {
            mat.glossy_samples = integer(Node{v, path("glossy_samples")}, 1, 4096);
        }
        if (const Json* v = find(m, "texture"))
            mat.texture = read_texture(Node{v, path("texture")}, scene);
        if (const Json* v = find(m, "texture_specular")) {
            mat.texture_specular = boolean(Node{v, path("texture_specular")});
        }
        if (const Json* v = find(m, "reflection")) {
            Node r{v, path("reflection")};
            mat.reflection = real(r, Sign::non_negative);
            if (mat.reflection > 2.0f) fail(r, "must be from 0 to 2");
        }
        if (const Json* v = find(m, "k_a_after")) {
            mat.k_a_after = real(Node{v, path("k_a_after")}, Sign::non_negative);
        }
        if (const Json* v = find(m, "fresnel")) mat.fresnel = boolean(Node{v, path("fresnel")});
        if (const Json* v = find(m, "refraction")) {
            Node r{v, path("refraction")};
            expect_keys(r, {"ior", "filter"});
            mat.refractive = true;
            if (const Json* i = find(r, "ior")) {
                Node ior{i, member_path(r.path, "ior")};
                mat.ior = real(ior, Sign::positive);
                if (mat.ior < 1e-3f || mat.ior > 1e3f) fail(ior, "must be from 0.001 to 1000");
            }
            if (const Json* f = find(r, "filter")) {
                Node fn{f, member_path(r.path, "filter")};
                mat.filter = color(fn);
                if (mat.filter.x > 1.0f || mat.filter.y > 1.0f || mat.filter.z > 1.0f) {
                    fail(fn,
                         "must be at most 1 in every channel (a transmittance per unit length)");
                }
            }
        }
        if (const Json* v = find(m, "env_map"))
            mat.env_map = read_texture(Node{v, path("env_map")}, scene);
        if (const Json* v = find(m, "normal_map")) {
            mat.normal_map = read_texture(Node{v, path("normal_map")}, scene);
        }
        if (const Json* v = find(m, "normal_map_mode")) {
            mat.normal_map_mode =
                choice(Node{v, path("normal_map_mode")}, {"tangent", "replace"}) == 0
                    ? NormalMapMode::tangent
                    : NormalMapMode::replace;
        }
        if (const Json* v = find(m, "emission")) mat.emission = color(Node{v, path("emission")});
        return mat;
    }

    Light read_light(const Node& n, Scene& scene) {
        expect(n, n.j->is_object(), "an object");
        int type = choice(child(n, "type"), {"point", "directional", "rect", "disk", "box"});
        Light light;
        constexpr LightKind kinds[] = {LightKind::point, LightKind::directional, LightKind::rect,
                                       LightKind::disk, LightKind::box};
        light.kind = kinds[type];
        auto path = [&](std::string_view key) { return member_path(n.path, key); };
        switch (light.kind) {
            case LightKind::point:
                expect_keys(n, {"type", "position", "color", "intensity", "shadows"});
                light.position = point(child(n, "position"));
                break;
            case LightKind::directional:
                expect_keys(n, {"type", "direction", "color", "intensity", "shadows"});
                light.direction = direction(child(n, "direction"));
                break;
            case LightKind::rect: {
                expect_keys(n, {"type", "corner", "edge_u", "edge_v", "color", "intensity",
                                "shadows", "samples", "visible"});
                light.position = point(child(n, "corner"));
                light.edge_u = vector(child(n, "edge_u"));
                Node ev = child(n, "edge_v");
                light.edge_v = vector(ev);
                if (!(glm::length(glm::cross(light.edge_u, light.edge_v)) > 0.0f)) {
                    fail(ev, "the rectangle has zero area (edges parallel or zero)");
                }
                break;
            }
            case LightKind::disk:
                expect_keys(n, {"type", "center", "normal", "radius", "color", "intensity",
                                "shadows", "samples", "visible"});
                light.position = point(child(n, "center"));
                light.direction = direction(child(n, "normal"));
                light.radius = real(child(n, "radius"), Sign::positive);
                break;
            case LightKind::box: {
                expect_keys(n, {"type", "min", "max", "color", "intensity", "shadows", "samples",
                                "visible"});
                Node hi = child(n, "max");
                light.position = point(child(n, "min"));
                const vec3 top = point(hi);
                if (!(light.position.x <= top.x && light.position.y <= top.y &&
                      light.position.z <= top.z)) {
                    fail(hi, "must be >= min in every component");
                }
                light.edge_u = top - light.position;
                break;
            }
        }
        if (const Json* v = find(n, "color")) light.color = color(Node{v, path("color")});
        if (const Json* v = find(n, "intensity")) {
            light.intensity = real(Node{v, path("intensity")}, Sign::non_negative);
        }
        if (const Json* v = find(n, "shadows")) light.shadows = boolean(Node{v, path("shadows")});
        const double brightest = std::max({light.color.x, light.color.y, light.color.z});
        if (!(brightest * double(light.intensity) <= double(std::numeric_limits<float>::max())))
            fail(n, "the light's color times its intensity overflows the float range");
        if (light.is_area()) {
            check_area_light(n, light);
            light.samples = 16;
            if (const Json* v = find(n, "samples")) {
                light.samples = integer(Node{v, path("samples")}, 1, 4096);
            }
            bool visible = true;
            if (const Json* v = find(n, "visible")) visible = boolean(Node{v, path("visible")});
            if (visible) add_emitter(light, scene);
        }
        return light;
    }

    /// Area lights whose derived geometry or emission would leave the float range (or whose
    /// stand-in would be degenerate) are errors: nothing infinite may reach the image.
    void check_area_light(const Node& n, const Light& light) const {
        auto finite3 = [](vec3 v) {
            return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
        };
        const vec3 far = light.position + light.edge_u + light.edge_v;
        if (!finite3(light.edge_u) || !finite3(far)) {
            fail(n, "the light's extent overflows the float range");
        }
        if (light.kind == LightKind::disk && !(1e-3f * light.radius > 1e-30f)) {
            fail(child(n, "radius"), "is too small (must be > 1e-27)");
        }
        if (!(double(light.intensity) / (4.0 * std::numbers::pi * emitter_area(light)) < 1e30)) {
            fail(n, "the light's emitted radiance overflows (intensity too large for its area)");
        }
    }

    /// The report's "2ab" of an area light's stand-in (twice the area of a rectangle or disc;
    /// 2ab for a box with a, b its two largest extents); 1 when degenerate.
    static double emitter_area(const Light& light) {
        double area = 0.0;
        const glm::dvec3 e(light.edge_u);
        if (light.kind == LightKind::rect) {
            area = 2.0 * glm::length(glm::cross(e, glm::dvec3(light.edge_v)));
        } else if (light.kind == LightKind::disk) {
            area = 2.0 * std::numbers::pi * double(light.radius) * light.radius;
        } else {
            double a = std::max(e.x, e.y), b = std::max(e.x, e.z);
            if (a == b) b = std::max(e.y, e.z);
            area = 2.0 * a * b;
        }
        return area > 0.0 ? area : 1.0;
    }

    /// The visible stand-in of an area light (report-scenes.md 1.4): an object of emitted
    /// radiance colour * intensity / (4 pi A) that casts no shadows. A is the report's "2ab":
    /// twice the area of a rectangle or disc, 2ab for a box with a, b its two largest extents.
    void add_emitter(const Light& light, Scene& scene) {
        Material m;
        m.name = "<area light " + std::to_string(scene.lights.size()) + ">";
        Object o;
        o.casts_shadows = false;
        o.material = uint32_t(scene.materials.size());
        Transform t;
        switch (light.kind) {
            case LightKind::rect: {
                const vec3 p = light.position, u = light.edge_u, v = light.edge_v;
                const Triangle tris[2] = {{p, p + u, p + u + v}, {p, p + u + v, p + v}};
                for (const Triangle& tri : tris) {
                    o.kind = ShapeKind::triangle;
                    o.shape = uint32_t(scene.triangles.size());
                    scene.triangles.push_back(tri);
                    scene.objects.push_back(o);
                }
                break;
            }
            case LightKind::disk: {
                const double r = light.radius;
                // a thin cylinder whose axis (+y) is the disc normal
                const glm::dvec3 n(light.direction);
                const glm::dvec3 a =
                    std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
                const glm::dvec3 tangent = glm::normalize(glm::cross(n, a));
                t.rotate = glm::dmat3(tangent, n, glm::cross(tangent, n));
                const double h = 1e-3 * r;
                t.translate = glm::dvec3(light.position) - 0.5 * h * n;
                o.kind = ShapeKind::cylinder;
                o.shape = uint32_t(scene.cylinders.size());
                scene.cylinders.push_back(Cylinder{float(r), float(h)});
                set_transform(o, t);
                scene.objects.push_back(o);
                break;
            }
            case LightKind::box: {
                o.kind = ShapeKind::box;
                o.shape = uint32_t(scene.boxes.size());
                scene.boxes.push_back(Box{light.position, light.position + light.edge_u});
                scene.objects.push_back(o);
                break;
            }
            default:
                return;
        }
        const double area = emitter_area(light);
        m.emission = light.color * float(double(light.intensity) / (4.0 * std::numbers::pi * area));
        add_material(scene, m);
    }

    Transform read_transform(const Node& n) const {
        expect_keys(n, {"translate", "rotate", "rotate_deg", "scale"});
        Transform t;
        if (const Json* v = find(n, "translate")) {
            t.translate = dvec3(Node{v, member_path(n.path, "translate")});
        }
        const Json* rotate = find(n, "rotate");
        const Json* rotate_deg = find(n, "rotate_deg");
        if (rotate && rotate_deg) {
            fail(child(n, "rotate_deg"), "give either rotate or rotate_deg, not both");
        }
        if (rotate) {
            Node list{rotate, member_path(n.path, "rotate")};
            expect(list, rotate->is_array(), "an array of {\"axis\", \"deg\"} rotations");
            // Written as a product, like T * R * S: the last rotation is applied first.
            for (size_t i = 0; i < rotate->size(); ++i) {
                Node r{&(*rotate)[i], element_path(list.path, i)};
                expect_keys(r, {"axis", "deg"});
                int axis = choice(child(r, "axis"), {"x", "y", "z"});
                t.rotate = t.rotate * make_rotation(axis, number(child(r, "deg")));
            }
        }
        if (rotate_deg) {
            t.rotate =
                make_rotation_xyz(dvec3(Node{rotate_deg, member_path(n.path, "rotate_deg")}));
        }
        if (const Json* v = find(n, "scale")) {
            Node s{v, member_path(n.path, "scale")};
            if (v->is_number()) {
                t.scale = glm::dvec3(number(s));
            } else {
                expect(s, v->is_array() && v->size() == 3, "a number or an array of 3 numbers");
                t.scale = dvec3(s);
            }
            if (t.scale.x == 0.0 || t.scale.y == 0.0 || t.scale.z == 0.0) {
                fail(s, "must not be zero (the transform would not be invertible)");
            }
        }
        return t;
    }

    uint32_t material_index(const Node& object, Scene& scene) {
        std::string name = "default";
        const Json* v = find(object, "material");
        if (v) name = text(Node{v, member_path(object.path, "material")});
        if (const auto it = material_ids_.find(name); it != material_ids_.end()) return it->second;
        if (v) {
            std::vector<std::string> known;
            for (const Material& m : scene.materials) known.push_back(m.name);
            fail(Node{v, member_path(object.path, "material")},
                 "no material named " + json_quoted(name) + " (known: " + join(known, 20) + ")");
        }
        Material fallback;  // an object without "material" gets scene.h's defaults
        fallback.name = name;
        return add_material(scene, fallback);
    }

    /// The "fit" normalisation of a mesh with the given bounds (see transform.h, make_fit).
    glm::dmat4 read_fit(const Node& n, const Aabb& bounds) const {
        expect_keys(n, {"size", "axis", "scale", "offset"});
        const Json* size = find(n, "size");
        const Json* scale = find(n, "scale");
        if (size && scale) fail(child(n, "scale"), "give either size or scale, not both");
        if (!size && !scale) fail(n, "needs \"size\" or \"scale\"");
        double s = 0.0;
        if (scale) {
            if (find(n, "axis")) fail(child(n, "axis"), "only goes with \"size\"");
            s = number(child(n, "scale"), Sign::positive);
        } else {
            int axis = bounds.empty() ? 0 : bounds.longest_axis();
            if (const Json* v = find(n, "axis")) {
                int a = choice(Node{v, member_path(n.path, "axis")}, {"x", "y", "z", "longest"});
                if (a < 3) axis = a;
            }
            double extent = bounds.empty() ? 0.0 : double(bounds.extent()[axis]);
            if (!(extent > 0.0)) {
                fail(n, std::string("the mesh has no extent along ") + "xyz"[axis] + " to fit");
            }
            s = number(child(n, "size"), Sign::positive) / extent;
        }
        glm::dvec3 offset(0.0);
        if (const Json* v = find(n, "offset")) {
            offset = dvec3(Node{v, member_path(n.path, "offset")});
        }
        return make_fit(bounds, s, offset);
    }

    void read_object(const Node& n, Scene& scene) {
        expect(n, n.j->is_object(), "an object");
        constexpr ShapeKind kinds[] = {ShapeKind::sphere, ShapeKind::box,      ShapeKind::cylinder,
                                       ShapeKind::plane,  ShapeKind::triangle, ShapeKind::mesh};
        Object object;
        object.kind = kinds[choice(child(n, "shape"),
                                   {"sphere", "box", "cylinder", "plane", "triangle", "mesh"})];
        switch (object.kind) {
            case ShapeKind::sphere:
                expect_keys(n, {"shape", "material", "transform", "center", "radius"});
                break;
            case ShapeKind::box:
                expect_keys(n, {"shape", "material", "transform", "min", "max"});
                break;
            case ShapeKind::cylinder:
                expect_keys(n, {"shape", "material", "transform", "radius", "height"});
                break;
            case ShapeKind::plane:
                expect_keys(n, {"shape", "material", "transform", "point", "normal"});
                break;
            case ShapeKind::triangle:
                expect_keys(n, {"shape", "material", "transform", "vertices"});
                break;
            case ShapeKind::mesh:
                expect_keys(n, {"shape", "material", "transform", "file", "fit", "normals"});
                break;
        }
        object.material = material_index(n, scene);
        Transform t;
        if (const Json* v = find(n, "transform")) {
            t = read_transform(Node{v, member_path(n.path, "transform")});
        }
        // A shape with a transform (and every cylinder and mesh) is given in its own space and
        // the transform takes it to the world; without one its points are world points. Either
        // way it moves with the world origin.
        const bool own_space =
            !is_identity(t) || object.kind == ShapeKind::cylinder || object.kind == ShapeKind::mesh;
        if (own_space) t.translate -= world_origin_;
        auto shape_point = [&](const Node& p) { return own_space ? vector(p) : point(p); };
        const vec3 shape_origin = own_space ? vec3(0.0f) : vec3(-world_origin_);

        switch (object.kind) {
            case ShapeKind::sphere: {
                Sphere s;
                s.center = shape_origin;
                if (const Json* v = find(n, "center")) {
                    s.center = shape_point(Node{v, member_path(n.path, "center")});
                }
                s.radius = real(child(n, "radius"), Sign::positive);
                object.shape = uint32_t(scene.spheres.size());
                scene.spheres.push_back(s);
                break;
            }
            case ShapeKind::box: {
                Box b;
                Node hi = child(n, "max");
                b.lo = shape_point(child(n, "min"));
                b.hi = shape_point(hi);
                if (!(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z)) {
                    fail(hi, "must be >= min in every component");
                }
                object.shape = uint32_t(scene.boxes.size());
                scene.boxes.push_back(b);
                break;
            }
            case ShapeKind::cylinder: {
                Cylinder c;
                c.radius = real(child(n, "radius"), Sign::positive);
                c.height = real(child(n, "height"), Sign::positive);
                object.shape = uint32_t(scene.cylinders.size());
                scene.cylinders.push_back(c);
                break;
            }
            case ShapeKind::plane: {
                Plane p;
                p.point = shape_origin;
                if (const Json* v = find(n, "point")) {
                    p.point = shape_point(Node{v, member_path(n.path, "point")});
                }
                p.normal = direction(child(n, "normal"));
                object.shape = uint32_t(scene.planes.size());
                scene.planes.push_back(p);
                break;
            }
            case ShapeKind::triangle: {
                Node verts = child(n, "vertices");
                expect(verts, verts.j->is_array() && verts.j->size() == 3, "an array of 3 points");
                Triangle tri;
                tri.p0 = shape_point(Node{&(*verts.j)[0], element_path(verts.path, 0)});
                tri.p1 = shape_point(Node{&(*verts.j)[1], element_path(verts.path, 1)});
                tri.p2 = shape_point(Node{&(*verts.j)[2], element_path(verts.path, 2)});
                glm::dvec3 e1 = glm::dvec3(tri.p1) - glm::dvec3(tri.p0);
                glm::dvec3 e2 = glm::dvec3(tri.p2) - glm::dvec3(tri.p0);
                if (glm::cross(e1, e2) == glm::dvec3(0.0)) {
                    fail(verts, "the triangle has zero area");
                }
                object.shape = uint32_t(scene.triangles.size());
                scene.triangles.push_back(tri);
                break;
            }
            case ShapeKind::mesh:
                // Baked into world space: the object keeps the identity transform.
                read_mesh(n, t, scene);
                object.shape = uint32_t(scene.meshes.size() - 1);
                scene.objects.push_back(object);
                return;
        }
        set_transform(object, t);
        if (!all_finite(object.world_from_object) || !all_finite(object.object_from_world)) {
            fail(find(n, "transform") ? child(n, "transform") : n,
                 "the matrix overflows the float range");
        }
        scene.objects.push_back(object);
    }

    /// Loads (once per file), fits and bakes a mesh into world space; appends it to scene.meshes.
    void read_mesh(const Node& n, const Transform& t, Scene& scene) {
        Node file = child(n, "file");
        std::string name = text(file);
        std::string resolved;
        try {
            resolved = find_model(name, dir_);
        } catch (const InputError& e) {
            fail(file, e.what());
        }
        auto it = meshes_.find(resolved);
        if (it == meshes_.end()) it = meshes_.emplace(resolved, load_mesh(resolved)).first;
        // the file's last object takes the mesh: a copy is megabytes of fresh pages
        const bool last_use = --mesh_uses_[resolved] <= 0;
        Mesh mesh = last_use ? std::move(meshes_.extract(it).mapped()) : it->second;
        if (mesh.name.empty()) mesh.name = name;
        // normals: "auto" (the file's, else smooth), "file", "smooth" or "flat"
        const char* modes[] = {"auto", "file", "smooth", "flat"};
        const int mode = find(n, "normals")
                             ? choice(child(n, "normals"), {modes[0], modes[1], modes[2], modes[3]})
                             : 0;
        if (mode == 1 && mesh.normal_tris.empty())
            fail(child(n, "normals"), "the mesh file has no normals");
        if (mode == 2 || (mode == 0 && mesh.normal_tris.empty())) compute_smooth_normals(mesh);
        if (mode == 3) drop_normals(mesh);
        glm::dmat4 world_from_object = make_world_from_object(t);
        if (const Json* v = find(n, "fit")) {
            world_from_object = world_from_object *
                                read_fit(Node{v, member_path(n.path, "fit")}, mesh_bounds(mesh));
        }
        bake_transform(mesh, world_from_object);
        for (vec3 p : mesh.positions) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                fail(n, "the transform moves mesh positions outside the float range");
            }
        }
        scene.meshes.push_back(std::move(mesh));
    }

    static bool all_finite(const mat4& m) {
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) {
                if (!std::isfinite(m[c][r])) return false;
            }
        }
        return true;
    }
};

}  // namespace

Scene load_scene_from_string(std::string_view json, const std::string& path_for_errors) {
    Json root = parse_json(json, path_for_errors, max_scene_json_depth);
    std::string dir = std::filesystem::path(path_for_errors).parent_path().string();
    if (dir.empty()) dir = ".";
    return SceneReader(path_for_errors, dir).read(root);
}

Scene load_scene(const std::string& path) {
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
