// io: Wavefront OBJ meshes -> scene/scene.h MeshData. Sibling of load_ply.h; load_mesh.h picks one.
#pragma once

#include <string>
#include <string_view>

#include "scene/scene.h"

namespace raylane {

/// Reads an OBJ file into a MeshData (positions, normals, uvs with their own index triples); a
/// name ending in .gz is a gzip-compressed file, decompressed into memory first (gzip_file.h),
/// and line numbers in messages count in the decompressed text.
///
/// Accepted: `v x y z [w | r g b]`, `vt u [v [w]]`, `vn x y z`, and `f` in every index form
/// (`v`, `v/vt`, `v//vn`, `v/vt/vn`) with positive or negative (relative) indices; an index
/// left empty is absent, as common readers take it (`7/` and `7//` are the form `v`, `7/2/` is
/// `v/vt`); polygons are split into a fan (c0, ci, ci+1). Faces may refer to vertices defined later
/// in the file. LF, CR LF or CR-only line ends (mixed too), tabs and runs of spaces between tokens,
/// a UTF-8 byte order mark, `#` comments (also after the values of a line) and a missing final
/// newline are fine.
///
/// Materials: `usemtl name` gives the faces that follow that material (MeshData::material_names,
/// MeshData::tri_material); faces before any `usemtl`, or after a bare one, get the material named
/// "" (the object's own); `mtllib` names go to MeshData::material_libraries, as written. The scene
/// loader reads the libraries (load_mtl.h).
///
/// Ignored: `o g s l p` and any other keyword (`vp`, `curv`, ...), i.e. any line whose first
/// token is a letter followed by letters, digits or '_'.
///
/// Normals and uvs are kept only when every face has them: if some faces lack `vn` (or `vt`)
/// the mesh gets no normals (or uvs) at all, and normal_tris / uv_tris are empty.
///
/// Refused before parsing, with one line that says what the file is (text_form.h): an empty
/// file ("file: is empty"), UTF-16 text, gzip data under a name without .gz, and a binary file
/// ("file: is a binary file, not a text OBJ (byte N is 0xNN)").
///
/// Errors (InputError "file:line: reason"): a line starting with anything but a keyword,
/// `#` or whitespace; a bad or missing number; NaN or infinite values; index 0; an index
/// out of range (reported on the line of the first face using it); a face with fewer than 3
/// corners; a face mixing index forms; a file without faces. Not supported: `\` line
/// continuation.
MeshData load_obj(const std::string& path);

/// Same as load_obj on text already in memory; `name_for_errors` prefixes messages and
/// gives the mesh its name.
MeshData load_obj_from_memory(std::string_view text, const std::string& name_for_errors);

}  // namespace raylane
