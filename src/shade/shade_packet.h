// shade: the report's local shading of W hits (diffuse + Phong, shadow packets to every light),
// the packet path. Mirrors shade_scalar.h.
#pragma once

#include <cstdint>

#include "accel/bvh.h"
#include "core/ray_packet.h"
#include "scene/scene.h"
#include "shade/shade_scalar.h"

namespace raylane {

/// Radiance towards the ray origins for the active lanes (all must be hits); the formula of
/// shade_hit, lane by lane. Shadow rays are traced as packets and counted in `counts`.
template <int W>
Vec3<W> shade_hit(const Scene& scene, const Accel& accel, const RayPacket<W>& rays,
                  const HitPacket<W>& hits, vmask<W> active, ShadeCounts& counts);

}  // namespace raylane
