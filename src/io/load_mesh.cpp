// io: mesh reader dispatch by extension (load_mesh.h).
#include "io/load_mesh.h"

#include <filesystem>
#include <string>
#include <system_error>

#include "core/error.h"
#include "io/load_obj.h"
#include "io/load_ply.h"
#include "io/read_file.h"

namespace raylane {

Mesh load_mesh(const std::string& path) {
    const std::string name = file_name_of(path);
    const size_t dot = name.find_last_of('.');
    std::string extension = dot == std::string::npos ? std::string() : name.substr(dot);
    for (char& c : extension) {
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    }
    std::error_code error;
    const auto bytes = std::filesystem::file_size(path, error);  // (regular files only)
    if (!error && bytes > static_cast<uintmax_t>(max_mesh_file_bytes)) {
        throw InputError(path + ": file is " + std::to_string(bytes) +
                         " bytes, over the limit of 2^31 for a mesh");
    }
    if (extension == ".obj") return load_obj(path);
    if (extension == ".ply") return load_ply(path);
    throw InputError(
        path + ": unsupported mesh format " +
        (extension.empty() ? std::string("(no extension)") : quote_for_error(extension)) +
        "; expected .obj or .ply");
}

}  // namespace raylane
