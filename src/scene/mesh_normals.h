// scene: vertex normals for meshes that come without them.
#pragma once

#include "scene/scene.h"

namespace raylane {

/// Replaces the mesh's normals by area-weighted averages of the face normals around each
/// position (the report's bunny normals), on the winding's side. A vertex whose faces cancel
/// out gets no usable normal: it keeps a zero vector and shading falls back to the face normal.
void compute_smooth_normals(MeshData& mesh);

/// dp/du of triangle `prim` from its positions and uvs (the tangent of tangent-space normal
/// maps); the zero vector when the mesh has no uvs or the uv triangle is degenerate.
vec3 triangle_dpdu(const MeshData& mesh, uint32_t prim);

/// Drops the mesh's normals: shading uses the face normal (faceted look).
void drop_normals(MeshData& mesh);

}  // namespace raylane
