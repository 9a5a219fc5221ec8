// io: Stanford PLY meshes -> scene/scene.h MeshData. Sibling of load_obj.h; load_mesh.h picks one.
#pragma once

#include <string>
#include <string_view>

#include "scene/scene.h"

namespace raylane {

/// Reads a PLY 1.0 file: `ascii`, `binary_little_endian` or `binary_big_endian`. A name ending
/// in .gz is a gzip-compressed file, decompressed into memory first (gzip_file.h); line and
/// byte numbers in messages count in the decompressed bytes.
///
/// Header lines: format, element, property, comment, obj_info, end_header (blank lines are
/// skipped). Property types: char uchar short ushort int uint float double and their sized
/// names int8 ... float64.
/// - Element `vertex`: x y z (required), nx ny nz (optional, all three), uvs from the first of
///   the pairs (u v), (s t), (texture_u texture_v), (texture_s texture_t); any numeric type,
///   any order. Other properties are skipped.
/// - Element `face`: a list property `vertex_indices` (or `vertex_index`) with integer count
///   and item types; polygons are split into a fan. Other properties are skipped.
/// - Other elements, before or after, are skipped (list properties included).
/// normal_tris and uv_tris equal tris when the vertices carry normals / uvs.
///
/// Lines (of the header and of ASCII bodies) may end in LF, CR LF or CR alone. ASCII bodies
/// hold one record per line (blank lines skipped); binary bytes after the last
/// element are ignored. No more records are allocated than the bytes (binary) or lines (ASCII)
/// left can hold.
///
/// A file that ends before the records the header promised says where it ends and how many of
/// them it held: "file:LINE: ends after K of N vertices" (ASCII; LINE is the file's last line,
/// and a last line without an end while records are still promised is cut short and not
/// counted: "... (the last line is cut short)"), "file: byte SIZE: ends after K of N faces"
/// (binary; K whole records), "'edge' records" for other elements; a list count that runs past
/// the end: "file: byte N: list count C in 'vertex_indices' needs B bytes, but only R remain:
/// the file ends after K of N faces".
///
/// Errors (InputError "file:line: reason" in the header and in ASCII bodies, "file: byte N:
/// reason" in binary bodies): an empty file ("file: is empty"); UTF-16 text or gzip data under
/// a name without .gz, said as such (text_form.h); otherwise a missing magic, unknown header line,
/// unsupported format or version, missing x/y/z or vertex_indices, an early end (above), too few or
/// too many values on an ASCII line, bad or out-of-range numbers, NaN or infinite vertex
/// attributes, negative list count, face with fewer than 3 vertices, vertex index out of range, a
/// file without faces.
MeshData load_ply(const std::string& path);

/// Same as load_ply on bytes already in memory; `name_for_errors` prefixes messages and gives
/// the mesh its name.
MeshData load_ply_from_memory(std::string_view bytes, const std::string& name_for_errors);

}  // namespace raylane
