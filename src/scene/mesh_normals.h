// scene: vertex normals for meshes that come without them.
#pragma once

#include "scene/scene.h"

namespace raylane {

/// Replaces the mesh's normals by area-weighted averages of the face normals around each
/// position (the report's bunny normals), on the winding's side. A vertex whose faces cancel
/// out gets no usable normal: it keeps a zero vector and shading falls back to the face normal.
void compute_smooth_normals(Mesh& mesh);

/// Drops the mesh's normals: shading uses the face normal (faceted look).
void drop_normals(Mesh& mesh);

}  // namespace raylane
