// shade: the report's local shading of W hits (diffuse + Phong, shadow packets to every light),
// the packet path. Mirrors shade_scalar.h.
#pragma once

#include <cstdint>

#include "accel/bvh.h"
#include "core/ray_packet.h"
#include "scene/scene.h"
#include "shade/shade_scalar.h"

namespace raylane {

/// Radiance towards the ray origins of a block of packets, for the active lanes (all must be
/// hits): the formula of shade_hit, lane by lane. Per light, the block's shadow rays are traced
/// together (intersect_any_block) and counted in `counts`. count * W <= max_block_rays.
template <int W>
void shade_hit(const Scene& scene, const Accel& accel, const RayPacket<W>* rays,
               const HitPacket<W>* hits, const vmask<W>* active, int count, Vec3<W>* color,
               ShadeCounts& counts);

}  // namespace raylane
