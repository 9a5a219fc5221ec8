// io: model search path (model_path.h).
#include "io/model_path.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace raylane {

namespace fs = std::filesystem;

namespace {

bool is_file(const fs::path& path) {
    std::error_code error;
    return fs::is_regular_file(path, error);
}

void add_dir(std::vector<std::string>& dirs, const fs::path& dir) {
    std::string normal = dir.lexically_normal().string();
    if (normal.size() > 1 && normal.back() == '/') normal.pop_back();
    for (const std::string& d : dirs) {
        if (d == normal) return;
    }
    dirs.push_back(normal);
}

}  // namespace

std::vector<std::string> model_search_dirs(const std::string& scene_dir) {
    std::vector<std::string> dirs;
    add_dir(dirs, scene_dir.empty() ? fs::path(".") : fs::path(scene_dir));
    if (const char* env = std::getenv("RAYLANE_MODEL_PATH")) {
        std::string_view list(env);
        while (!list.empty()) {
            size_t colon = list.find(':');
            std::string_view entry = list.substr(0, colon);
            if (!entry.empty()) add_dir(dirs, fs::path(entry));
            list = colon == std::string_view::npos ? std::string_view() : list.substr(colon + 1);
        }
    }
    add_dir(dirs, fs::path(RAYLANE_SOURCE_DIR "/../shared/models"));
    add_dir(dirs, fs::path(RAYLANE_SOURCE_DIR "/../shared/textures"));
    std::error_code error;
    fs::path cwd = fs::current_path(error);
    if (!error) {
        add_dir(dirs, cwd / "../shared/models");
        add_dir(dirs, cwd / "../shared/textures");
    }
    return dirs;
}

std::string find_model(const std::string& name, const std::string& scene_dir) {
    if (name.empty()) throw InputError("model name is empty");
    const fs::path model(name);
    std::vector<std::string> searched;
    if (model.is_absolute()) {
        if (is_file(model)) return name;
        searched.push_back(model.parent_path().string());
    } else {
        searched = model_search_dirs(scene_dir);
        for (const std::string& dir : searched) {
            fs::path candidate = fs::path(dir) / model;
            if (is_file(candidate)) return candidate.string();
        }
    }
    std::string list;
    for (const std::string& dir : searched) list += (list.empty() ? "" : ", ") + dir;
    throw InputError(name + ": model not found; looked in: " + list +
                     ". Get it from the Stanford 3D Scanning Repository "
                     "(https://graphics.stanford.edu/data/3Dscanrep/) or put its folder in "
                     "RAYLANE_MODEL_PATH (':'-separated)");
}

}  // namespace raylane
