// traverse: closest-hit and any-hit queries of a block of coherent packets (a tile's camera
// rays and their shadow rays), the packet path's answer to rays that stay together.
#pragma once

#include "accel/bvh.h"
#include "core/ray_packet.h"
#include "scene/scene.h"

namespace raylane::RAYLANE_ISA_NS {

/// Most rays a block may hold: a 16 x 16 tile.
inline constexpr int max_block_rays = 256;

/// intersect_closest for a block of coherent packets (a tile's primary rays, say): the same
/// answers lane by lane, but the block is traversed as a whole. A node is tested against the
/// packets in order until one hits it (most nodes cost one test); a node that no packet can hit,
/// by interval arithmetic over the block's origins and reciprocal directions, is culled at once
/// (ranged traversal: Overbeck, Ramamoorthi, Mark, "Large Ray Packets for Real-time Whitted Ray
/// Tracing", IEEE RT 2008; interval culling: Wald, Boulos, Shirley, "Ray Tracing Deformable
/// Scenes Using Dynamic Bounding Volume Hierarchies", ACM TOG 2007). count * W <= max_block_rays.
template <int W>
void intersect_closest_block(const SceneData& scene, const Accel& accel, const RayPacket<W>* rays,
                             const vmask<W>* active, HitPacket<W>* hits, int count);

/// intersect_any for a block of packets; occluded[p] receives the lanes of packet p that hit.
template <int W>
void intersect_any_block(const SceneData& scene, const Accel& accel, const RayPacket<W>* rays,
                         const vmask<W>* active, vmask<W>* occluded, int count);

}  // namespace raylane::RAYLANE_ISA_NS
