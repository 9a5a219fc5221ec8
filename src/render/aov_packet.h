// render: the packet renderer's analysis images (AOVs: normal, depth, BVH cost), a tile's
// packets at a time. The scalar renderer computes them pixel by pixel (render_scalar.cpp).
#pragma once

#include "accel/bvh.h"
#include "core/ray_packet.h"
#include "render/render_params.h"
#include "scene/scene.h"

namespace raylane::RAYLANE_ISA_NS {

/// One sample's values of a non-colour AOV (normal, depth, BVH cost) for a block of `count`
/// packets (a tile, at most max_block_rays rays); colour gives black.
template <int W>
void aov_values(const SceneData& scene, const Accel& accel, const RayPacket<W>* rays,
                const vmask<W>* active, int count, Aov aov, Vec3<W>* value);

}  // namespace raylane::RAYLANE_ISA_NS
