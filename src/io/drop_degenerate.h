// io: removes triangles that span no area from a freshly loaded mesh (numerics.md section 8).
#pragma once

#include <string>

#include "scene/scene.h"

namespace raylane {

/// Drops every triangle whose cross product is exactly zero in double (repeated or collinear
/// vertices: never hit, no normal) together with its uv and normal triangles and its material
/// index, and counts them in
/// mesh.dropped_triangles. Slivers with any area stay. Throws InputError "name: ..." when no
/// triangle is left.
void drop_zero_area_triangles(MeshData& mesh, const std::string& name_for_errors);

}  // namespace raylane
