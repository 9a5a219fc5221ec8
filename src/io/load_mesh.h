// io: picks the mesh reader by file extension (load_obj.h, load_ply.h).
#pragma once

#include <string>

#include "scene/scene.h"

namespace raylane {

/// load_obj for ".obj", load_ply for ".ply" (extension compared case-insensitively).
/// Any other extension throws InputError "path: unsupported mesh format ...".
Mesh load_mesh(const std::string& path);

}  // namespace raylane
