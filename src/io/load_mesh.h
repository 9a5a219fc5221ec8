// io: picks the mesh reader by file extension (load_obj.h, load_ply.h).
#pragma once

#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace raylane {

/// Largest mesh file read (bytes, 2 GiB): a bigger file is refused before it is mapped.
inline constexpr int64_t max_mesh_file_bytes = int64_t{1} << 31;

/// load_obj for ".obj" and ".obj.gz", load_ply for ".ply" and ".ply.gz" (extensions compared
/// case-insensitively; .gz files are gzip-compressed, gzip_file.h). A file over
/// max_mesh_file_bytes throws InputError "path: file is N bytes, over the limit of 2^31 for a
/// mesh" before anything is read (for .gz files the decompressed bytes have the same limit); any
/// other extension "path: unsupported mesh format ...".
MeshData load_mesh(const std::string& path);

/// The lower-case extension of `path`'s file name as load_mesh reads it: ".obj", ".obj.gz" for
/// a compressed one, ".gz" or "" when there is no other.
std::string mesh_extension(const std::string& path);

}  // namespace raylane
