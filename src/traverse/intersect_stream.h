// traverse: closest hits of a stream of incoherent rays (bounce, glossy and refracted rays),
// the packet path's answer to lanes that diverge: the rays are regrouped at every node.
#pragma once

#include <cstdint>

#include "accel/bvh.h"
#include "core/ray_packet.h"
#include "scene/scene.h"

namespace raylane::RAYLANE_ISA_NS {

/// Most rays one stream may hold (ray numbers times 8, the records' floats, stay in an int32).
inline constexpr int64_t max_stream_rays = int64_t(1) << 28;

/// intersect_closest for `count` packets of rays with no coherence assumed: the same answers
/// lane by lane. The rays go down each BVH together as a list of ray numbers that is split at
/// every node into the rays that touch each child, tested W at a time whichever packet they
/// came from, so that the tests stay full where a packet's lanes would have parted (stream
/// traversal: Barringer, Akenine-Moeller, "Dynamic Ray Stream Traversal", ACM TOG 33(4), 2014).
/// Inside a mesh's BVH a list of at most W rays goes on as one packet (the packet traversal of
/// that subtree). Worth it from about a thousand rays; any count up to max_stream_rays works.
template <int W>
void intersect_closest_stream(const SceneData& scene, const Accel& accel, const RayPacket<W>* rays,
                              const vmask<W>* active, HitPacket<W>* hits, int count);

/// intersect_any for `count` packets by the same stream traversal: occluded[p] receives the
/// lanes of packet p that hit anything in (t_min, t_max). A ray leaves every list once it is
/// occluded. `occluded` must not be `active`.
template <int W>
void intersect_any_stream(const SceneData& scene, const Accel& accel, const RayPacket<W>* rays,
                          const vmask<W>* active, vmask<W>* occluded, int count);

}  // namespace raylane::RAYLANE_ISA_NS
