// traverse: the surface at W hits of the packet path (surface_at): positions, normals, uv,
// materials. Mirrors surface_scalar.h.
#pragma once

#include "core/ray_packet.h"
#include "scene/scene.h"

namespace raylane::RAYLANE_ISA_NS {

/// Everything shading needs about W hits, in world space (the twin of SurfacePoint).
template <int W>
struct SurfacePacket {
    Vec3<W> position;
    Vec3<W> geometric_normal;
    Vec3<W> shading_normal;
    vfloat<W> u = vfloat<W>(0.0f), v = vfloat<W>(0.0f);
    vint<W> material = vint<W>(0);
};

/// Evaluates position, normals and uv at the active lanes' hits (all must be hits). MeshData hits
/// are evaluated W at a time; analytic shapes lane by lane through the scalar surface_at
/// (surface_scalar.h).
template <int W>
SurfacePacket<W> surface_at(const SceneData& scene, const RayPacket<W>& rays,
                            const HitPacket<W>& hits, vmask<W> active);

}  // namespace raylane::RAYLANE_ISA_NS
