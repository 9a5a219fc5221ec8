// io: the scene loader's part for a model file's own materials: the MTL libraries an OBJ names
// (load_mtl.h), mapped onto Raylane's materials, textures and normal maps found next to them.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/scene_reader.h"

namespace raylane {

namespace {

/// Where the library `name` (as the model file wrote it, '\' made '/') is: in the model's folder.
std::string library_path(const std::string& model_path, const std::string& name) {
    std::string written = name;
    std::replace(written.begin(), written.end(), '\\', '/');
    return (std::filesystem::path(model_path).parent_path() / written).lexically_normal().string();
}

}  // namespace

/// The library `name` (as the model file wrote it, '\' made '/') from the model's folder, read
/// once; nullptr, with one warning, when it cannot be found or read.
const MtlLibrary* SceneReader::material_library(const std::string& model_path,
                                                const std::string& name, SceneData& scene) {
    const std::string key = library_path(model_path, name);
    if (const auto it = libraries_.find(key); it != libraries_.end())
        return it->second ? &*it->second : nullptr;
    std::optional<MtlLibrary>& lib = libraries_[key];
    try {
        lib = load_mtl(key);
    } catch (const InputError& e) {
        scene.warnings.push_back(model_path + ": material library " + name +
                                 " not read, its faces get the default material (" + e.what() +
                                 ")");
        return nullptr;
    }
    if (!lib->ignored.empty()) {
        std::string keys;
        for (const std::string& k : lib->ignored) keys += (keys.empty() ? "" : ", ") + k;
        scene.warnings.push_back(key + ": ignored " + keys +
                                 " (Raylane has no transparency, and no maps beyond map_Kd and "
                                 "map_Bump/bump/norm)");
    }
    return &*lib;
}

/// Raylane's material for an MTL material, its textures found from the library's folder (a
/// texture that cannot be read: one warning, and none).
Material SceneReader::mtl_material(const MtlMaterial& m, const std::string& library_path,
                                   SceneData& scene) {
    Material out = material_from_mtl(m);
    const std::filesystem::path dir = std::filesystem::path(library_path).parent_path();
    auto texture = [&](const std::string& file, ImageEncoding encoding) -> int32_t {
        const std::string path = (dir / file).lexically_normal().string();
        try {
            return texture_from_file(path, encoding, TextureFilter::bilinear, true, scene);
        } catch (const InputError& e) {
            scene.warnings.push_back(library_path + ": material " + m.name + ": " + e.what() +
                                     "; left out");
            return -1;
        }
    };
    if (!m.map_kd.empty()) out.texture = texture(m.map_kd, ImageEncoding::srgb);
    if (!m.map_bump.empty()) out.normal_map = texture(m.map_bump, ImageEncoding::linear);
    return out;
}

/// The material of a model's faces that name `name`: the scene's material of that name (a scene
/// overrides a model's materials by name), else the first library's definition of it, else
/// `fallback` (the default material) with one warning.
uint32_t SceneReader::model_material(const std::string& name, const std::string& model_path,
                                     const std::vector<std::string>& libraries, uint32_t fallback,
                                     SceneData& scene) {
    if (const auto it = material_ids_.find(name); it != material_ids_.end()) return it->second;
    for (const std::string& lib_name : libraries) {
        const MtlLibrary* lib = material_library(model_path, lib_name, scene);
        if (!lib) continue;
        for (const MtlMaterial& m : lib->materials) {
            if (m.name != name) continue;
            return add_material(scene, mtl_material(m, library_path(model_path, lib_name), scene));
        }
    }
    scene.warnings.push_back(model_path + ": material " + name +
                             (libraries.empty() ? " named, but the file names no mtllib"
                                                : " is in none of its libraries") +
                             "; its faces get the default material");
    return fallback;
}

}  // namespace raylane
