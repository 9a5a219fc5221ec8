// traverse: ray/box (axis-aligned box primitive) intersection, the reference path (one ray,
// object space). Mirrored by box_packet.h.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/ray.h"
#include "scene/scene.h"
#include "traverse/local_geometry.h"
#include "traverse/slab_scalar.h"

namespace raylane {

/// Nearest t in the open interval (ray.t_min, ray.t_max) where the ray meets the box, or
/// infinity; the exit t when the origin is inside. The slab test of slab_scalar.h with the
/// same conventions (far distance scaled by slab_far_scale for the decision, so a box of zero
/// thickness crossed by the ray is hit; closed test; a ray lying in a face plane counts as
/// inside that slab), except that NaN inputs and rays lying in a zero-thickness slab miss.
inline float intersect_box(const Box& b, const Ray& ray) {
    const vec3 inv_dir = reciprocal(ray.dir);
    float t_enter = -infinity;
    float t_exit = infinity;
    for (int i = 0; i < 3; ++i) {
        // slab i: near/far by the sign of inv_dir (-0.0 gives -inf)
        const float t_lo = (b.lo[i] - ray.org[i]) * inv_dir[i];
        const float t_hi = (b.hi[i] - ray.org[i]) * inv_dir[i];
        const bool neg = inv_dir[i] < 0.0f;
        const float t_near = neg ? t_hi : t_lo;
        const float t_far = neg ? t_lo : t_hi;

        // NaN: for one plane only (0 * inf, the ray lies in that face plane) the slab stays open
        // on that side; for both planes (a NaN input, or the ray lies in a slab of zero
        // thickness) the box is missed
        if (!(t_lo == t_lo || t_hi == t_hi)) return infinity;

        // interval: NaN-safe updates (a NaN leaves the bound unchanged)
        t_enter = t_near > t_enter ? t_near : t_enter;
        t_exit = t_far < t_exit ? t_far : t_exit;
    }
    // decide: closed test against the inflated exit (Ize 2013)
    if (!(t_enter <= t_exit * slab_far_scale)) return infinity;

    // accept: the entry, or the exit when the entry is not after t_min (origin inside)
    if (t_enter > ray.t_min && t_enter < ray.t_max) return t_enter;
    if (t_exit > ray.t_min && t_exit < ray.t_max) return t_exit;
    return infinity;
}

/// Normal and uv at an object-space point p on the box. The face is the one whose plane is
/// nearest to p; ties (edges, corners, zero thickness) go to x before y before z, and to the lo
/// face before the hi face. uv are p's coordinates on the face along the next two axes in cyclic
/// order (x: y, z; y: z, x; z: x, y), scaled to [0, 1] (0 along an axis of zero extent).
inline LocalGeometry geometry_box(const Box& b, vec3 p) {
    // face: nearest plane, strict < keeps the earlier axis on ties
    int axis = 0;
    float side = -1.0f;
    float best = infinity;
    for (int i = 0; i < 3; ++i) {
        const float d_lo = std::abs(p[i] - b.lo[i]);
        const float d_hi = std::abs(p[i] - b.hi[i]);
        const float d = d_lo <= d_hi ? d_lo : d_hi;
        if (d < best) {
            best = d;
            axis = i;
            side = d_lo <= d_hi ? -1.0f : 1.0f;
        }
    }
    LocalGeometry g;
    g.normal = vec3(0.0f);
    g.normal[axis] = side;

    // uv: position on the face
    const int iu = (axis + 1) % 3;
    const int iv = (axis + 2) % 3;
    const vec3 extent = b.hi - b.lo;
    const float u = extent[iu] > 0.0f ? (p[iu] - b.lo[iu]) / extent[iu] : 0.0f;
    const float v = extent[iv] > 0.0f ? (p[iv] - b.lo[iv]) / extent[iv] : 0.0f;
    g.uv = vec2(std::clamp(u, 0.0f, 1.0f), std::clamp(v, 0.0f, 1.0f));
    return g;
}

}  // namespace raylane
