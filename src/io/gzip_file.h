// io: gzip-compressed model files (RFC 1952) inflated into memory with zlib, and the choice
// between that and mapping the file as it is (read_file.h). Used by load_obj.cpp, load_ply.cpp.
#pragma once

#include <cstddef>
#include <string>

#include "io/read_file.h"

namespace raylane {

/// Largest decompressed model (bytes, 2 GiB): the limit load_mesh.h puts on a plain mesh file.
inline constexpr size_t max_inflated_bytes = size_t{1} << 31;

/// Whether `path` ends in ".gz" (compared case-insensitively).
bool has_gzip_extension(const std::string& path);

/// The decompressed bytes of the gzip file `path`, held once: the compressed file is read in
/// 64 KiB chunks and inflated (zlib, gzip framing) straight into one block of anonymous
/// memory, sized from the gzip trailer's length field and grown, when that is short, by
/// remapping pages rather than copying them. Members one after another (`cat a.gz b.gz`) are
/// read in turn. Throws InputError, one line naming `path`: "cannot read: reason", "is empty",
/// "is not gzip data (it does not start with 1f 8b)", "gzip data is corrupt at compressed byte
/// N (zlib: reason)", "gzip data ends early, after N compressed bytes", "data after the end of
/// the gzip data at compressed byte N", "decompresses to more than 2^31 bytes, over the limit
/// for a mesh" (`max_bytes` below max_inflated_bytes, for tests: "more than MAX bytes").
FileBytes inflate_file(const std::string& path, size_t max_bytes = max_inflated_bytes);

/// inflate_file(path) when the name ends in .gz, else map_file(path): how the mesh readers
/// get a file's bytes.
FileBytes read_model_file(const std::string& path);

}  // namespace raylane
