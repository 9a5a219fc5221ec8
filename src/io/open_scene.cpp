// io: a path opened as a scene: the built-in scene, a model file's own scene or a JSON scene.
#include "io/open_scene.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/error.h"
#include "io/load_scene.h"
#include "io/model_scene.h"

namespace raylane {

namespace {

bool has_extension(const std::string& path, const std::string& ext) {
    std::string e = std::filesystem::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return e == ext;
}

/// Whether the file's first character that is not white space is '{' (a JSON object).
bool starts_like_json(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char c = 0;
    while (in.get(c))
        if (!std::isspace(static_cast<unsigned char>(c))) return c == '{';
    return false;
}

}  // namespace

std::string scene_file_problem(const std::string& path) {
    std::error_code error;
    const std::filesystem::file_status status = std::filesystem::status(path, error);
    if (std::filesystem::is_regular_file(status)) return {};
    if (std::filesystem::is_directory(status))
        return "is a folder, not a scene (.json) or a model (.obj, .ply)";
    if (std::filesystem::exists(status)) return "is not a regular file (a device, pipe or socket)";
    return "no such file";
}

SceneData open_scene(const std::string& path) {
    if (path.empty()) return make_builtin_scene();
    if (const std::string problem = scene_file_problem(path); !problem.empty())
        throw InputError(path + ": " + problem);
    if (!is_model_file(path) && !has_extension(path, ".json") && !starts_like_json(path))
        throw InputError(path +
                         ": neither a scene nor a model: expected a JSON scene (.json) or a "
                         "model (.obj, .ply, .obj.gz, .ply.gz)");
    return is_model_file(path) ? load_model_scene(path) : load_scene(path);
}

}  // namespace raylane
