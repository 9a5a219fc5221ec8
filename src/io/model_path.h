// io: where model files (meshes named by scenes) are looked up. Used by io/load_scene.cpp.
#pragma once

#include <string>
#include <vector>

namespace raylane {

/// The folders find_model searches for a relative name, in order, without duplicates:
/// `scene_dir` ("." when empty), then each non-empty entry of RAYLANE_MODEL_PATH
/// (':'-separated). Textures and environment maps are looked up the same way.
std::vector<std::string> model_search_dirs(const std::string& scene_dir);

/// What find_model looks for: a mesh ("model not found") or an image ("image not found").
enum class ModelKind { mesh, texture };

/// The path of the file `name`: `name` itself when absolute, else the first of
/// model_search_dirs(scene_dir) that holds it as a regular file. When there is none, throws
/// InputError with one line naming the file and every folder searched by its full name (the
/// scene's folder, RAYLANE_MODEL_PATH's or that it is not set; where to get it for a Stanford
/// model: the bunny, the dragon and their kin), or, when a folder holds
/// `name` as something else (a folder, a device, a pipe, a broken link), what it is. A name
/// holding a NUL byte is an error too (the system would read the name only up to it).
std::string find_model(const std::string& name, const std::string& scene_dir,
                       ModelKind kind = ModelKind::mesh);

}  // namespace raylane
