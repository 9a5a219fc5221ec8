// io: mesh reader dispatch by extension (load_mesh.h).
#include "io/load_mesh.h"

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
    if (extension == ".obj") return load_obj(path);
    if (extension == ".ply") return load_ply(path);
    throw InputError(
        path + ": unsupported mesh format " +
        (extension.empty() ? std::string("(no extension)") : quote_for_error(extension)) +
        "; expected .obj or .ply");
}

}  // namespace raylane
