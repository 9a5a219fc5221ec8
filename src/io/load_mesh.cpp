// io: mesh reader dispatch by extension (load_mesh.h).
#include "io/load_mesh.h"

#include <filesystem>
#include <string>
#include <system_error>

#include "core/error.h"
#include "io/gzip_file.h"
#include "io/load_obj.h"
#include "io/load_ply.h"
#include "io/read_file.h"

namespace raylane {

std::string mesh_extension(const std::string& path) {
    std::string name = file_name_of(path);
    for (char& c : name) {
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    }
    const size_t stem_end = has_gzip_extension(name) ? name.size() - 3 : name.size();
    const size_t dot = name.find_last_of('.', stem_end == 0 ? 0 : stem_end - 1);
    return dot == std::string::npos ? name.substr(stem_end) : name.substr(dot);
}

MeshData load_mesh(const std::string& path) {
    static_assert(max_inflated_bytes == static_cast<size_t>(max_mesh_file_bytes));
    std::error_code error;
    const auto bytes = std::filesystem::file_size(path, error);  // (regular files only)
    if (!error && bytes > static_cast<uintmax_t>(max_mesh_file_bytes)) {
        throw InputError(path + ": file is " + std::to_string(bytes) +
                         " bytes, over the limit of 2^31 for a mesh");
    }
    const std::string extension = mesh_extension(path);
    if (extension == ".obj" || extension == ".obj.gz") return load_obj(path);
    if (extension == ".ply" || extension == ".ply.gz") return load_ply(path);
    throw InputError(
        path + ": unsupported mesh format " +
        (extension.empty() ? std::string("(no extension)") : quote_for_error(extension)) +
        "; expected .obj or .ply, or either with .gz");
}

}  // namespace raylane
