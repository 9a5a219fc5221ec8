// io: model search path (model_path.h).
#include "io/model_path.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace raylane {

namespace fs = std::filesystem;

namespace {

/// Whether `path` names a regular file (following links): empty when it does, "missing" when
/// nothing is there, else why it is not one.
std::string file_problem(const fs::path& path) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (fs::is_regular_file(status)) return {};
    if (fs::exists(status)) {
        return fs::is_directory(status) ? "is a folder, not a file"
                                        : "is not a regular file (a device, pipe or socket)";
    }
    // a link loop is said; other errors (a folder this user may not search, a file name under
    // a file) count as missing, so the message does not depend on who runs it
    if (error == std::errc::too_many_symbolic_link_levels) return error.message();
    if (fs::is_symlink(fs::symlink_status(path, error))) return "is a link to nothing";
    return "missing";
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
    return dirs;
}

std::string find_model(const std::string& name, const std::string& scene_dir, ModelKind kind) {
    if (name.empty()) throw InputError("file name is empty");
    if (name.find('\0') != std::string::npos) {
        std::string shown = name;
        for (size_t at = 0; (at = shown.find('\0', at)) != std::string::npos; at += 2)
            shown.replace(at, 1, "\\0");
        throw InputError(shown + ": a file name must not contain a NUL byte");
    }
    const fs::path model(name);
    std::vector<std::string> searched;
    std::string problem;  // the first candidate that is there but is not a regular file
    auto found = [&](const fs::path& candidate) {
        const std::string why = file_problem(candidate);
        if (!why.empty() && why != "missing" && problem.empty())
            problem = candidate.string() + ": " + why;
        return why.empty();
    };
    if (model.is_absolute()) {
        if (found(model)) return name;
        searched.push_back(model.parent_path().string());
    } else {
        searched = model_search_dirs(scene_dir);
        for (const std::string& dir : searched) {
            fs::path candidate = fs::path(dir) / model;
            if (found(candidate)) return candidate.string();
        }
    }
    if (!problem.empty()) throw InputError(problem);
    std::string list;
    for (const std::string& dir : searched) list += (list.empty() ? "" : ", ") + dir;
    if (kind == ModelKind::texture)
        throw InputError(name + ": image not found; looked in: " + list +
                         ". Put its folder in RAYLANE_MODEL_PATH (':'-separated)");
    throw InputError(name + ": model not found; looked in: " + list +
                     ". Get it from the Stanford 3D Scanning Repository "
                     "(https://graphics.stanford.edu/data/3Dscanrep/) or put its folder in "
                     "RAYLANE_MODEL_PATH (':'-separated)");
}

}  // namespace raylane
