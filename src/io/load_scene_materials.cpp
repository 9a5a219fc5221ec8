// io: the materials of the scene format (SceneReader, io/scene_reader.h): each material's BRDF
// parameters, fitted presets, refraction, and the textures and maps they name.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.h"
#include "io/load_image.h"
#include "io/model_path.h"
#include "io/scene_reader.h"
#include "scene/brdf_presets.h"

namespace raylane {

uint32_t SceneReader::add_material(SceneData& scene, Material m) {
    const uint32_t index = uint32_t(scene.materials.size());
    material_ids_.emplace(m.name, index);
    scene.materials.push_back(std::move(m));
    return index;
}

/// A texture given as a file name, {"file", "filter", "encoding", "repeat"} or
/// {"checker": [colour a, colour b], "checks"}; loaded once per file and options.
int32_t SceneReader::read_texture(const Node& n, SceneData& scene) {
    Texture options;
    ImageEncoding encoding = ImageEncoding::linear;
    std::string file;
    if (n.j->is_string()) {
        file = text(n);
    } else {
        expect_keys(n, {"file", "filter", "encoding", "repeat", "checker", "checks"});
        if (const Json* v = find(n, "checker")) {
            if (find(n, "file")) fail(child(n, "file"), "give either file or checker, not both");
            Node c{v, member_path(n.path, "checker")};
            expect(c, v->is_array() && v->size() == 2, "an array of two colours");
            float checks = 8.0f;
            if (const Json* k = find(n, "checks")) {
                checks = real(Node{k, member_path(n.path, "checks")}, Sign::positive);
            }
            scene.textures.push_back(make_checker(color(Node{&(*v)[0], element_path(c.path, 0)}),
                                                  color(Node{&(*v)[1], element_path(c.path, 1)}),
                                                  checks));
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
    try {
        return texture_from_file(resolved, encoding, options.filter, options.repeat, scene);
    } catch (const InputError& e) {
        fail(file_node, e.what());
    }
}

/// The texture of a found file with these options, loaded once per file and options.
int32_t SceneReader::texture_from_file(const std::string& resolved, ImageEncoding encoding,
                                       TextureFilter filter, bool repeat, SceneData& scene) {
    const std::string key = resolved + (encoding == ImageEncoding::srgb ? "|srgb" : "|lin") +
                            (filter == TextureFilter::nearest ? "|n" : "|b") +
                            (repeat ? "|r" : "|c");
    if (auto it = textures_.find(key); it != textures_.end()) return it->second;
    Texture t = load_texture(resolved, encoding);
    t.filter = filter;
    t.repeat = repeat;
    scene.textures.push_back(std::move(t));
    textures_[key] = int32_t(scene.textures.size() - 1);
    return textures_[key];
}

void SceneReader::read_materials(const Node& n, SceneData& scene) {
    expect(n, n.j->is_object(), "an object");
    for (auto it = n.j->begin(); it != n.j->end(); ++it) {
        Node m{&it.value(), member_path(n.path, it.key())};
        if (it.key().empty()) fail(m, "a material name must not be empty");
        add_material(scene, read_material(m, it.key(), scene));
    }
}

Material SceneReader::read_material(const Node& m, const std::string& name, SceneData& scene) {
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
    read_brdf(m, mat);
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
    if (const Json* v = find(m, "refraction")) read_refraction(Node{v, path("refraction")}, mat);
    if (const Json* v = find(m, "env_map"))
        mat.env_map = read_texture(Node{v, path("env_map")}, scene);
    if (const Json* v = find(m, "normal_map")) {
        mat.normal_map = read_texture(Node{v, path("normal_map")}, scene);
    }
    if (const Json* v = find(m, "normal_map_mode")) {
        mat.normal_map_mode = choice(Node{v, path("normal_map_mode")}, {"tangent", "replace"}) == 0
                                  ? NormalMapMode::tangent
                                  : NormalMapMode::replace;
    }
    if (const Json* v = find(m, "emission")) mat.emission = color(Node{v, path("emission")});
    return mat;
}

/// The diffuse and specular lobes: the model, a fitted preset, then the parameters given.
void SceneReader::read_brdf(const Node& m, Material& mat) const {
    auto path = [&](std::string_view key) { return member_path(m.path, key); };
    if (const Json* v = find(m, "model")) {
        constexpr SpecularModel models[] = {SpecularModel::phong, SpecularModel::glossy_phong,
                                            SpecularModel::blinn_phong, SpecularModel::ward,
                                            SpecularModel::ward_duer};
        mat.model = models[choice(Node{v, path("model")},
                                  {"phong", "glossy-phong", "blinn-phong", "ward", "ward-duer"})];
    }
    if (const Json* v = find(m, "preset")) {
        Node p{v, path("preset")};
        bool merl = false;
        if (const Json* c = find(m, "merl_colour")) merl = boolean(Node{c, path("merl_colour")});
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
    if (const Json* v = find(m, "k_d")) mat.k_d = real(Node{v, path("k_d")}, Sign::non_negative);
    if (const Json* v = find(m, "k_a")) mat.k_a = real(Node{v, path("k_a")}, Sign::non_negative);
    if (const Json* v = find(m, "c_s")) mat.c_s = color(Node{v, path("c_s")});
    if (const Json* v = find(m, "k_s")) mat.k_s = real(Node{v, path("k_s")}, Sign::non_negative);
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
}

/// A glass material's {"ior", "filter"}.
void SceneReader::read_refraction(const Node& r, Material& mat) const {
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
            fail(fn, "must be at most 1 in every channel (a transmittance per unit length)");
        }
    }
}

uint32_t SceneReader::material_index(const Node& object, SceneData& scene) {
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

}  // namespace raylane
