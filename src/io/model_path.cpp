// io: model search path (model_path.h).
#include "io/model_path.h"

#include <cstdlib>
#include <filesystem>
#include <string_view>
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

/// Whether `name` is one of the Stanford 3D Scanning Repository's models (the bunny, the dragon,
/// the Buddha, the armadillo, Lucy and the XYZ RGB scans), which the scenes name but the
/// repository does not hold.
bool is_stanford_model(const std::string& name) {
    const std::string stem = fs::path(name).stem().string();
    for (const char* known : {"bunny", "dragon", "happy", "armadillo", "lucy", "xyzrgb"})
        if (stem.rfind(known, 0) == 0) return true;
    return false;
}

/// The folders a relative name was looked for in, by their real names: the scene's folder (or
/// the current one), then RAYLANE_MODEL_PATH's, or that it is unset.
std::string searched_folders(const std::string& scene_dir) {
    auto real = [](const fs::path& dir) {
        std::error_code error;
        const fs::path full = fs::weakly_canonical(fs::absolute(dir, error), error);
        return (error || full.empty() ? dir : full).string();
    };
    std::string out = scene_dir.empty() ? "the current folder " + real(".")
                                        : "the scene's folder " + real(scene_dir);
    const char* env = std::getenv("RAYLANE_MODEL_PATH");
    if (env == nullptr || *env == '\0') return out + " (RAYLANE_MODEL_PATH is not set)";
    std::string list;
    std::string_view rest(env);
    while (!rest.empty()) {
        const size_t colon = rest.find(':');
        const std::string_view entry = rest.substr(0, colon);
        if (!entry.empty()) list += (list.empty() ? "" : ", ") + real(fs::path(entry));
        rest = colon == std::string_view::npos ? std::string_view() : rest.substr(colon + 1);
    }
    return out + " and RAYLANE_MODEL_PATH's " + list;
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
    std::string problem;  // the first candidate that is there but is not a regular file
    auto found = [&](const fs::path& candidate) {
        const std::string why = file_problem(candidate);
        if (!why.empty() && why != "missing" && problem.empty())
            problem = candidate.string() + ": " + why;
        return why.empty();
    };
    if (model.is_absolute()) {
        if (found(model)) return name;
    } else {
        for (const std::string& dir : model_search_dirs(scene_dir)) {
            fs::path candidate = fs::path(dir) / model;
            if (found(candidate)) return candidate.string();
        }
    }
    if (!problem.empty()) throw InputError(problem);
    const std::string what = kind == ModelKind::texture ? "image" : "model";
    if (model.is_absolute()) throw InputError(name + ": " + what + " not found (no such file)");
    throw InputError(name + ": " + what + " not found; looked in " + searched_folders(scene_dir) +
                     ". Put its folder in RAYLANE_MODEL_PATH (':'-separated)" +
                     (kind == ModelKind::mesh && is_stanford_model(name)
                          ? ", or get it from the Stanford 3D Scanning Repository "
                            "(https://graphics.stanford.edu/data/3Dscanrep/)"
                          : ""));
}

}  // namespace raylane
