// traverse: closest-hit and any-hit queries of W rays against the whole scene (both BVH
// levels), the packet path. Mirrors intersect_scalar.h. Blocks of coherent packets:
// intersect_block.h; streams of incoherent rays: intersect_stream.h.
#pragma once

#include "accel/bvh.h"
#include "core/ray_packet.h"
#include "scene/scene.h"

namespace raylane::RAYLANE_ISA_NS {

/// The rays moved into an object's space; t is unchanged. Same products and sums as glm's
/// mat4 * vec4 on the scalar path: (c0 x + c1 y) + (c2 z + c3 w).
template <int W>
inline RayPacket<W> to_object_space(const Object& object, const RayPacket<W>& rays) {
    if (!object.has_transform) return rays;
    const mat4& m = object.object_from_world;
    RayPacket<W> r = rays;
    auto row = [&](int k, const Vec3<W>& p, float w) {
        return (vfloat<W>(m[0][k]) * p.x + vfloat<W>(m[1][k]) * p.y) +
               (vfloat<W>(m[2][k]) * p.z + vfloat<W>(m[3][k] * w));
    };
    r.org = {row(0, rays.org, 1.0f), row(1, rays.org, 1.0f), row(2, rays.org, 1.0f)};
    r.dir = {row(0, rays.dir, 0.0f), row(1, rays.dir, 0.0f), row(2, rays.dir, 0.0f)};
    return r;
}

/// The closest hit of each active lane in (t_min, t_max), with the scalar path's tie-break
/// (smaller t, then object, then primitive). Inactive lanes come back as misses.
/// `nodes_visited`, when given, counts per lane the BVH nodes tested while the lane was active.
template <int W>
HitPacket<W> intersect_closest(const SceneData& scene, const Accel& accel, const RayPacket<W>& rays,
                               vmask<W> active, vint<W>* nodes_visited = nullptr);

/// The active lanes that hit anything in (t_min, t_max) (shadow rays).
template <int W>
vmask<W> intersect_any(const SceneData& scene, const Accel& accel, const RayPacket<W>& rays,
                       vmask<W> active);

/// One object's part of intersect_closest: improves `hit` for the active lanes with the same
/// tie-break. A mesh's traversal starts at slot `start` of its wide tree without testing that
/// slot's box (the default: the root node): the caller knows the lanes reach it, or reached it
/// under a larger limit, which only costs tests. For the block and stream traversals.
template <int W>
void intersect_object_closest_from(const SceneData& scene, const Accel& accel, uint32_t object,
                                   const RayPacket<W>& rays, vmask<W> active, HitPacket<W>& hit,
                                   WideRef start = {});

/// One object's part of intersect_any: the active lanes it occludes (none when it casts no
/// shadows). A mesh from slot `start` of its wide tree, as intersect_object_closest_from.
template <int W>
vmask<W> intersect_object_any_from(const SceneData& scene, const Accel& accel, uint32_t object,
                                   const RayPacket<W>& rays, vmask<W> active, WideRef start = {});

}  // namespace raylane::RAYLANE_ISA_NS
