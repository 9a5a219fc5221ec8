// io: the scene a path names, whatever it is: a JSON scene file, a model file (its own scene),
// or nothing (the built-in scene); the command line, the library and Python all open scenes here.
#pragma once

#include <string>

#include "scene/scene.h"

namespace raylane {

/// The built-in scene when `path` is empty, a model file's own scene (io/model_scene.h) for .obj
/// and .ply (optionally .gz), else a JSON scene file. A file that is none of these (no .json
/// extension and not a JSON object) throws InputError saying what was expected; a path that is
/// missing or a folder throws scene_file_problem's line. The scene's warnings are left in
/// SceneData::warnings for the caller to show.
SceneData open_scene(const std::string& path);

/// Why `path` cannot be a scene or a model: "no such file", "is a folder, not a scene (.json) or
/// a model (.obj, .ply)", ...; empty when it is a file.
std::string scene_file_problem(const std::string& path);

}  // namespace raylane
