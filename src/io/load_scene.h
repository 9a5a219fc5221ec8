// io: the JSON scene loader (format: docs/scene-format.md). Produces the SceneData of
// scene/scene.h; meshes come through io/load_mesh.h, found by io/model_path.h.
#pragma once

#include <map>
#include <string>
#include <string_view>

#include "scene/scene.h"

namespace raylane {

/// Deepest nesting of JSON arrays and objects a scene file may have.
inline constexpr int max_scene_json_depth = 64;

/// Largest scene file load_scene reads, in bytes (meshes are separate files).
inline constexpr size_t max_scene_file_bytes = size_t{64} << 20;

/// Reads and checks a scene file. MeshData files are looked up from the file's folder.
/// Throws InputError with one line: "path: $.json.path: reason" for a bad value,
/// "path:line:column: reason" for malformed JSON; a mesh file's own InputError passes through.
SceneData load_scene(const std::string& path);

/// As load_scene, from text in memory. `path_for_errors` names the scene in messages and its
/// folder is where meshes are looked up first; it is stored in SceneData::source. `loaded` holds
/// meshes already read, by the path find_model gives for their file name: they are not read
/// again.
SceneData load_scene_from_string(std::string_view json, const std::string& path_for_errors,
                                 std::map<std::string, MeshData> loaded = {});

/// The folder a scene file's models are looked up in first: the file's own ("." when none).
std::string scene_dir(const std::string& scene_path);

}  // namespace raylane
