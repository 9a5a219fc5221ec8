// traverse: closest hits of a stream of incoherent rays (bounce, glossy and refracted rays),
// the packet path's answer to lanes that diverge: the rays are regrouped at every node.
#pragma once

#include "accel/bvh.h"
#include "core/ray_packet.h"
#include "scene/scene.h"

namespace raylane {

/// intersect_closest for `count` packets of rays with no coherence assumed: the same answers
/// lane by lane. The rays go down each BVH together as a list of ray numbers that is split at
/// every node into the rays that touch each child, tested W at a time whichever packet they
/// came from, so that the tests stay full where a packet's lanes would have parted (stream
/// traversal: Barringer, Akenine-Moeller, "Dynamic Ray Stream Traversal", ACM TOG 33(4), 2014).
/// A list of at most W rays goes on as one packet (intersect_closest's traversal of the
/// subtree). Worth it from about a thousand rays; any count works.
template <int W>
void intersect_closest_stream(const Scene& scene, const Accel& accel, const RayPacket<W>* rays,
                              const vmask<W>* active, HitPacket<W>* hits, int count);

/// intersect_any for `count` packets by the same stream traversal: occluded[p] receives the
/// lanes of packet p that hit anything in (t_min, t_max). A ray leaves every list once it is
/// occluded.
template <int W>
void intersect_any_stream(const Scene& scene, const Accel& accel, const RayPacket<W>* rays,
                          const vmask<W>* active, vmask<W>* occluded, int count);

}  // namespace raylane
