// traverse: closest-hit and any-hit queries of W rays against the whole scene (both BVH
// levels), the packet path. Mirrors intersect_scalar.h. Blocks of coherent packets:
// intersect_block.h; streams of incoherent rays: intersect_stream.h.
#pragma once

#include "accel/bvh.h"
#include "core/ray_packet.h"
#include "scene/scene.h"

namespace raylane::RAYLANE_ISA_NS {

/// The closest hit of each active lane in (t_min, t_max), with the scalar path's tie-break
/// (smaller t, then object, then primitive). Inactive lanes come back as misses.
/// `nodes_visited`, when given, counts per lane the BVH nodes tested while the lane was active.
template <int W>
HitPacket<W> intersect_closest(const Scene& scene, const Accel& accel, const RayPacket<W>& rays,
                               vmask<W> active, vint<W>* nodes_visited = nullptr);

/// The active lanes that hit anything in (t_min, t_max) (shadow rays).
template <int W>
vmask<W> intersect_any(const Scene& scene, const Accel& accel, const RayPacket<W>& rays,
                       vmask<W> active);

/// One object's part of intersect_closest: improves `hit` for the active lanes with the same
/// tie-break. A mesh's traversal starts at slot `start` of its wide tree without testing that
/// slot's box (the default: the root node): the caller knows the lanes reach it, or reached it
/// under a larger limit, which only costs tests. For the block and stream traversals.
template <int W>
void intersect_object_closest_from(const Scene& scene, const Accel& accel, uint32_t object,
                                   const RayPacket<W>& rays, vmask<W> active, HitPacket<W>& hit,
                                   WideRef start = {});

/// One object's part of intersect_any: the active lanes it occludes (none when it casts no
/// shadows). A mesh from slot `start` of its wide tree, as intersect_object_closest_from.
template <int W>
vmask<W> intersect_object_any_from(const Scene& scene, const Accel& accel, uint32_t object,
                                   const RayPacket<W>& rays, vmask<W> active, WideRef start = {});

/// Everything shading needs about W hits, in world space (the twin of SurfacePoint).
template <int W>
struct SurfacePacket {
    Vec3<W> position;
    Vec3<W> geometric_normal;
    Vec3<W> shading_normal;
    vfloat<W> u = vfloat<W>(0.0f), v = vfloat<W>(0.0f);
    vint<W> material = vint<W>(0);
};

/// Evaluates position, normals and uv at the active lanes' hits (all must be hits). Mesh hits
/// are evaluated W at a time; analytic shapes lane by lane through the scalar surface_at.
template <int W>
SurfacePacket<W> surface_at(const Scene& scene, const RayPacket<W>& rays, const HitPacket<W>& hits,
                            vmask<W> active);

}  // namespace raylane::RAYLANE_ISA_NS
